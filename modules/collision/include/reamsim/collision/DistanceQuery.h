#pragma once
// Query 2: minimum distance between the reamer's cutting face (its face triangles) and the bone, with the
// closest point pair. Exact up to rounding and a relative tolerance: the minimum over all triangle pairs of
// closestTriangleTriangle, found by branch and bound (a pair is skipped when a lower bound on its distance is
// within kDistanceRelativeTolerance of the best distance found, so the result is at most that much above the
// true minimum).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

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
  std::size_t nodesOpened = 0;       // bone tree nodes the search opened (a cost indicator)
};

DistanceResult queryFaceDistance(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                 double maxDistanceMm = std::numeric_limits<double>::infinity());

// Query 2 along a sequence of poses (a haptic or reaming loop, one tracker per loop): the same result as
// queryFaceDistance, exact in the same sense, and cheaper while the reamer hovers near the bone. A full
// search also collects the bone triangles whose lower bounds lie within `marginMm` beyond the distance d it
// found, so every other triangle is at least d + margin from the face. At a later pose no face point has
// moved more than m = |t1 - t0| + |R1 - R0|_F * (the face's radius about the tip); every other triangle is
// then at least d + margin - m away, and if the nearest collected one is no farther, it is the answer and
// the tree is not searched. Otherwise (moved too far, touching, the bone edited: TriangleBvh::revision(),
// another reamer) the full search runs and collects afresh. Where the face crossed the bone, the crossing
// pair is tried first. Poses are rigid (an orthonormal rotation), as for queryFaceDistance; a tracker serves one
// loop at a time (not thread-safe). See docs/COLLISION.md.
class FaceDistanceTracker {
 public:
  static constexpr double kDefaultMarginMm = 0.1;
  explicit FaceDistanceTracker(double marginMm = kDefaultMarginMm);

  DistanceResult query(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose);
  void reset() { valid_ = crossing_ = false; }

  struct Stats {
    std::size_t queries = 0;
    std::size_t searches = 0;  // full tree searches (the rest were answered without the tree)
  };
  const Stats& stats() const { return stats_; }

 private:
  double margin_;
  bool valid_ = false;
  std::uint64_t boneRevision_ = 0, faceRevision_ = 0;
  RigidTransform anchor_;        // pose of the last full search
  double anchorDistanceMm_ = 0;  // d there
  double reachMm_ = 0;           // d + margin: every triangle not collected is at least this far
  std::vector<std::uint32_t> collected_;
  bool crossing_ = false;  // the last search found the face crossing the bone, at this pair:
  std::uint32_t crossingBoneSlot_ = 0, crossingFaceSlot_ = 0;
  Stats stats_;
};

}  // namespace reamsim
