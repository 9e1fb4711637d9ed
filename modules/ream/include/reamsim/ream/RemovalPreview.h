#pragma once
// How much bone a "ream to depth" would take, computed on a copy of the bone before anything is cut: a surgeon
// compares depths, axes and reamers by what each removes, and the document is never touched.
#include <cstddef>
#include <optional>

#include "reamsim/core/BoneState.h"
#include "reamsim/core/Pose.h"
#include "reamsim/ream/ReamEngine.h"
#include "reamsim/tools/ReamedSurface.h"

namespace reamsim {

struct RemovalPreview {
  std::optional<double> approachMm;  // how far the reamer advances from `start` before it first touches the bone
  double depthMm = 0;                // below that contact, as asked
  double removedMm3 = 0;             // V(bone) − V(bone after the steps)
  std::size_t steps = 0, cuts = 0;   // the steps (the move to the contact, then the feed steps) and those that cut
  std::size_t facesAfter = 0;
  BoneState after;                   // the bone as the steps would leave it
  std::optional<Pose> lastPose;      // the last step's pose (none without contact)
  // The reamed surface under the face at the last pose (measureReamedSurface): how much of the face the bone
  // would seat; set by previewSeat, for a parametric reamer with a contact.
  std::optional<ReamedSurfaceReport> seat;
};

// Runs "ream to depth" (reamToDepthPoses: the move to the first contact within reachMm along start's axis, then
// feed steps of at most stepMm down to depthMm below it, each swept from the one before, the first from `start`)
// on `engine` against `bone`, as the reaming loop would, without a document. `engine` must be one of its own
// (its structures follow the copy; the session's engine is not to be used). No contact within reach: approachMm
// is unset and nothing is removed. `control` stops it before the search, between steps and between Booleans
// (ReamCancelled). Each call numbers its states apart, so one engine may be given different bones. Preconditions checked
// first: depthMm and stepMm positive and finite, reachMm positive, an engine that can collide and cut.
RemovalPreview previewReamToDepth(ReamEngine& engine, const BoneState& bone, const Pose& start, double depthMm,
                                  double stepMm, double reachMm, StepControl* control = nullptr);

// Sets preview.seat: the reamed surface of preview.after under the face of `spec` at preview.lastPose. Nothing
// without a contact or for a reamer read from a mesh (no ideal face). O(bone faces).
void previewSeat(RemovalPreview& preview, const ReamerSpec& spec);

}  // namespace reamsim
