#include "reamsim/collision/DistanceQuery.h"

#include <cmath>

#include "FaceDistanceSearch.h"
#include "QueryArguments.h"
#include "SurfaceTouch.h"

namespace reamsim {

using detail::FaceDistanceSearch;

namespace detail {
bool faceTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where,
                     std::size_t* nodesOpened) {
  if (bone.empty() || reamer.faceBvh().empty()) return false;
  DistanceResult out;
  FaceDistanceSearch search(bone, reamer, pose, FaceDistanceSearch::kInf, out);
  const bool crossing = search.findCrossing(false);
  if (nodesOpened) *nodesOpened += out.nodesOpened;
  if (!crossing) return false;
  if (where) *where = {out.boneSlot, out.reamerTriangle, out.onBone};
  return true;
}
}  // namespace detail

DistanceResult queryFaceDistance(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                 double maxDistanceMm) {
  detail::requireRigidPose(pose, "queryFaceDistance", "pose");
  DistanceResult out;
  if (bone.empty() || reamer.faceBvh().empty()) return out;
  const double max2 = maxDistanceMm < FaceDistanceSearch::kInf ? maxDistanceMm * maxDistanceMm : FaceDistanceSearch::kInf;
  FaceDistanceSearch search(bone, reamer, pose, max2, out);
  if (!search.findCrossing(true)) search.nearest();
  search.finish();
  return out;
}

}  // namespace reamsim
