#pragma once
// The thesis's proximity alerts, from the exact queries: "bounding boxes overlap" (with the minimum
// distance between the cutting face and the bone) and "contact" (the cutting volume touches the bone).
// Published into the document's AlertNode, which the GUI and the log observe.
#include <limits>
#include <vector>

#include "reamsim/collision/BoneCollider.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/core/AlertNode.h"

namespace reamsim {

struct ProximityStatus {
  bool boxesOverlap = false;  // bone box vs the box of the posed cutting solid (closed intervals)
  bool contact = false;       // query 1 (any touched face, or enclosed in a closed bone)
  double distanceMm = std::numeric_limits<double>::infinity();  // query 2, evaluated when the boxes overlap
};

ProximityStatus evaluateProximity(const BoneCollider& bone, const ReamerModel& reamer, const RigidTransform& pose);

// BoundsOverlap (with the distance) when the boxes overlap; Contact (distance 0) on contact.
std::vector<Alert> proximityAlerts(const ProximityStatus& status, NodeId reamer, NodeId bone);

// Replaces the node's alerts (AlertNode reports a modification only when they change).
void publishProximity(AlertNode& alerts, const ProximityStatus& status, NodeId reamer, NodeId bone);

}  // namespace reamsim
