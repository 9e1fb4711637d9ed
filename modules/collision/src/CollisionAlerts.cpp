#include "reamsim/collision/CollisionAlerts.h"

namespace reamsim {

ProximityStatus evaluateProximity(const BoneCollider& bone, const ReamerModel& reamer, const RigidTransform& pose) {
  ProximityStatus s;
  if (bone.bvh().empty()) return s;
  Bounds reamerBox;
  for (const Vec3& v : reamer.solid().vertices) reamerBox.add(pose.apply(v));
  s.boxesOverlap = reamerBox.overlaps(bone.bvh().bounds());
  if (!s.boxesOverlap) return s;
  s.contact = bone.overlap(reamer, pose, OverlapMode::AnyContact).overlap;
  s.distanceMm = bone.faceDistance(reamer, pose).distanceMm;
  return s;
}

std::vector<Alert> proximityAlerts(const ProximityStatus& status, NodeId reamer, NodeId bone) {
  std::vector<Alert> out;
  if (status.boxesOverlap) out.push_back({AlertKind::BoundsOverlap, reamer, bone, status.distanceMm});
  if (status.contact) out.push_back({AlertKind::Contact, reamer, bone, 0.0});
  return out;
}

void publishProximity(AlertNode& alerts, const ProximityStatus& status, NodeId reamer, NodeId bone) {
  alerts.setAlerts(proximityAlerts(status, reamer, bone));
}

}  // namespace reamsim
