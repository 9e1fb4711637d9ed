#include "reamsim/core/ReamerNode.h"

namespace reamsim {

void ReamerNode::setSpec(ReamerSpec spec) {
  spec_ = std::move(spec);
  cuttingVolume_.reset();
  markModified();
}

void ReamerNode::setPose(const Pose& pose) {
  pose_ = pose;
  markModified();
}

void ReamerNode::requestPlacement(const Pose& pose, bool clearOfBone) {
  placementRequest_ = PlacementRequest{pose, clearOfBone};
  markModified();
}

void ReamerNode::setCuttingVolume(std::shared_ptr<const TriangleMesh> mesh) {
  cuttingVolume_ = std::move(mesh);
  markModified();
}

}  // namespace reamsim
