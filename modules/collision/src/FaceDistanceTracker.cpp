// Query 2 along a sequence of poses: the collected-set shortcut between full searches (DistanceQuery.h).
#include <algorithm>
#include <cmath>

#include "FaceDistanceSearch.h"
#include "QueryArguments.h"
#include "reamsim/collision/DistanceQuery.h"

namespace reamsim {

namespace {

// Largest distance from the tip (the reamer-local origin) to a face point: the face BVH's root box's
// farthest corner.
double faceRadius(const ReamerModel& reamer) {
  const BvhNode& root = reamer.faceBvh().nodes()[reamer.faceBvh().root()];
  double r2 = 0;
  for (int i = 0; i < 3; ++i) r2 += std::max(root.lo[i] * root.lo[i], root.hi[i] * root.hi[i]);
  return std::sqrt(r2);
}

// Bound on how far any face point x (|x| <= radius) moves from pose a to pose b: |(Rb - Ra) x + tb - ta| <=
// |tb - ta| + |Rb - Ra|_F |x| (the Frobenius norm bounds the spectral one and needs no trace, whose rounding
// would dominate for the small turns between ticks). Padded for the rounding of the sums.
double movementBound(const RigidTransform& a, const RigidTransform& b, double radius) {
  double dr2 = 0;
  for (int i = 0; i < 9; ++i) dr2 += (b.rotation[i] - a.rotation[i]) * (b.rotation[i] - a.rotation[i]);
  const double m = norm(b.translation - a.translation) + std::sqrt(dr2) * radius;
  return m * (1 + 1e-12) + 1e-12 * (1 + radius + norm(a.translation) + norm(b.translation));
}

}  // namespace

FaceDistanceTracker::FaceDistanceTracker(double marginMm) : margin_(marginMm > 0 ? marginMm : kDefaultMarginMm) {}

DistanceResult FaceDistanceTracker::query(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose) {
  detail::requireRigidPose(pose, "FaceDistanceTracker::query", "pose");
  ++stats_.queries;
  DistanceResult out;
  if (bone.empty() || reamer.faceBvh().empty()) {
    valid_ = false;
    return out;
  }
  using detail::FaceDistanceSearch;
  const bool sameScene = bone.revision() == boneRevision_ && reamer.faceBvh().revision() == faceRevision_;
  if (crossing_ && sameScene) {
    // The face was in the bone: the pair that crossed then most likely still does (held against the bone).
    FaceDistanceSearch search(bone, reamer, pose, FaceDistanceSearch::kInf, out);
    if (search.crossesAt(crossingBoneSlot_, crossingFaceSlot_)) {
      search.finish();
      return out;
    }
  }
  if (valid_ && sameScene) {
    const double moved = movementBound(anchor_, pose, faceRadius(reamer));
    // Every triangle was at least d (up to the search's relative tolerance) from the face at the anchor, so
    // none can touch it now while d - moved > 0: the collected ones are measured as disjoint pairs.
    if (anchorDistanceMm_ * (1 - 4 * kDistanceRelativeTolerance) - moved > 0) {
      FaceDistanceSearch search(bone, reamer, pose, FaceDistanceSearch::kInf, out);
      search.nearestAmong(collected_);
      if (search.found() && std::sqrt(search.best2()) <= reachMm_ - moved) {
        search.finish();
        return out;
      }
    }
  }
  // A full search, collecting afresh (its pair count adds to the failed attempt's: both were spent).
  const std::size_t spentPairs = out.trianglePairs;
  out = DistanceResult{};
  ++stats_.searches;
  FaceDistanceSearch search(bone, reamer, pose, FaceDistanceSearch::kInf, out);
  valid_ = crossing_ = false;
  boneRevision_ = bone.revision();
  faceRevision_ = reamer.faceBvh().revision();
  if (search.findCrossing(true)) {
    crossing_ = true;
    crossingBoneSlot_ = out.boneSlot;
    crossingFaceSlot_ = search.bestFaceSlot();
  } else {
    search.nearestCollecting(margin_, collected_);
    if (search.found() && search.best2() > 0) {
      valid_ = true;
      anchor_ = pose;
      anchorDistanceMm_ = std::sqrt(search.best2());
      reachMm_ = search.reachMm();
    }
  }
  search.finish();
  out.trianglePairs += spentPairs;
  return out;
}

}  // namespace reamsim
