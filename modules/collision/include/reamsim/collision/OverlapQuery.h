#pragma once
// Query 1: does the reamer's cutting volume (closed solid) overlap the bone, and which bone triangles does
// it touch. A bone triangle is touched when it intersects the solid: it crosses or touches the solid's
// surface (trianglesIntersect, touching counts) or lies inside it. This set is what a cut replaces.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

enum class OverlapMode {
  AnyContact,       // stop at the first touched triangle (yes/no)
  AllTouchedFaces,  // collect every touched triangle
};

struct OverlapResult {
  bool overlap = false;  // touched faces exist, or (closed bone only) the solid sits entirely inside the bone
  bool reamerInsideBone = false;             // closed bone, no face touched, the solid is enclosed by the bone
  std::vector<std::uint32_t> touchedSlots;   // sorted bone slots (AnyContact: at most one)
  std::size_t surfaceCrossings = 0;          // touched faces that cross or touch the solid's surface
  std::size_t insideFaces = 0;               // touched faces entirely inside the solid
};

// `pose` maps reamer-local to bone coordinates. `boneClosed`: the bone is a closed surface, so a solid with
// no touched face may still be inside it (tested by crossing parity from the tip).
OverlapResult queryOverlap(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                           OverlapMode mode = OverlapMode::AllTouchedFaces, bool boneClosed = false);

}  // namespace reamsim
