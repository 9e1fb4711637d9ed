#pragma once
// Query 5: penetration depth of the reamer along its axis: how far it must back out along -axis until its
// cutting solid no longer overlaps the bone.
//
// Exact definition: backing out by d, two triangles (one of each surface) touch for d in a closed interval
// (the line d * axis through their Minkowski difference, a convex set), with ends at vertex-face and
// edge-edge events. depth = the end of the connected run of these intervals that starts at d = 0 (the
// surfaces touch at the pose) or, when the solid overlaps the bone without surface contact (enclosed), at
// the first contact when backing out. Bone farther behind the reamer that it would meet later does not
// count. 0 when the volumes do not overlap. A parametric reamer's face is taken as a height field across the
// axis (one interval per bone triangle); a reamer read from a file is paired triangle by triangle.
#include <cstddef>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

struct PenetrationResult {
  bool penetrating = false;  // the cutting solid overlaps the bone at the pose
  bool enclosed = false;     // ...without surface contact (solid inside a closed bone, or bone inside the solid)
  double depthMm = 0;
  Vec3 backOut;              // unit direction to back out (-axis)
  Vec3 lastContact;          // where the surfaces separate when backed out by depthMm (pose coordinates)
  std::size_t trianglePairs = 0;  // exact intervals solved: triangle pairs, or a bone triangle against a
                                  // parametric reamer's whole face (its face path, src/CapShadow.h)
};

inline constexpr double kChainToleranceRelative = 1e-9;  // x reamer radius: gap still counted as connected

PenetrationResult queryAxialPenetration(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                        bool boneClosed = false);

}  // namespace reamsim
