#pragma once
// Query 2: minimum distance between the reamer's cutting face (its face triangles) and the bone, with the
// closest point pair. Exact up to rounding and a relative tolerance: the minimum over all triangle pairs of
// closestTriangleTriangle, found by branch and bound (a pair is skipped when a lower bound on its distance is
// within kDistanceRelativeTolerance of the best distance found, so the result is at most that much above the
// true minimum).
#include <cstdint>
#include <limits>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

inline constexpr double kDistanceRelativeTolerance = 1e-9;

struct DistanceResult {
  bool found = false;  // false: nothing within maxDistance (distance stays +inf)
  double distanceMm = std::numeric_limits<double>::infinity();  // 0 when the face touches or crosses the bone
  Vec3 onReamer, onBone;      // closest pair, bone coordinates
  std::uint32_t boneSlot = 0;
  std::uint32_t reamerTriangle = 0;  // index into reamer.solid().triangles
  std::size_t trianglePairs = 0;     // exact triangle-pair evaluations (a cost indicator)
};

DistanceResult queryFaceDistance(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                 double maxDistanceMm = std::numeric_limits<double>::infinity());

}  // namespace reamsim
