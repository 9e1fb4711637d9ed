#pragma once
// Where on its axis to place the reamer so that placing it cuts nothing. Aim (the Planning dock) asks for the
// reamer a clearance out from the glenoid centre; at steep tilts, or on a bone already reamed, its rim reaches
// the bone there, and a placement cuts whatever the reamer overlaps. The answer is the nearest pose outward
// along the axis that is clear: the smallest retreat found, not the first contact coming in from afar (which
// would stop at a coracoid or acromion in the way and leave the reamer far out).
#include "reamsim/core/BoneState.h"
#include "reamsim/core/Pose.h"
#include "reamsim/ream/ReamEngine.h"

namespace reamsim {

struct ClearPlacement {
  enum class Outcome {
    AsAsked,      // the asked pose is clear
    Retreated,    // moved out along the axis by retreatMm
    NoRoom,       // nothing clear within maxRetreatMm: place nothing
    Unsupported,  // the engine has no exact contact query to ask (ReamEngine::touchesAt; one without overlapsAt
                  // gets the surface touch's answer)
  };
  Outcome outcome = Outcome::AsAsked;
  double retreatMm = 0;  // outward along the axis (Retreated)
  Pose pose;             // where to place it (the asked pose unless Retreated)
  int queries = 0;       // contact queries asked (surface touches and overlaps)
  bool overlapSearch = false;  // the answer on the surface touch overlapped the bone (the solid inside a closed
                               // bone, or a fragment inside the solid): searched again on the overlap itself
};

// Steps out from `asked` by stepMm until the reamer's cutting solid is clear of `bone` (overlaps none of it:
// ReamEngine::overlapsAt), bisects the last step down to ~stepMm / 256, and adds marginMm (checked clear too).
// `engine`: the reaming loop's, between computes, as advanceToContactMm. Preconditions checked first:
// maxRetreatMm, stepMm positive and finite, marginMm >= 0.
inline constexpr double kClearPlacementReachMm = 60;  // how far out the search looks by default
ClearPlacement findClearPlacement(ReamEngine& engine, const BoneState& bone, std::uint64_t revision, const Pose& asked,
                                  double maxRetreatMm = kClearPlacementReachMm, double stepMm = 0.5,
                                  double marginMm = 0.05);

}  // namespace reamsim
