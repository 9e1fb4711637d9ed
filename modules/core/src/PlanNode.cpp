#include "reamsim/core/PlanNode.h"

namespace reamsim {

void PlanNode::setReamerSpecName(std::string name) {
  reamerSpecName_ = std::move(name);
  markModified();
}

void PlanNode::setPoses(std::vector<Pose> poses) {
  poses_ = std::move(poses);
  markModified();
}

void PlanNode::addPose(const Pose& pose) {
  poses_.push_back(pose);
  markModified();
}

void PlanNode::setFeedDescription(std::optional<std::string> text) {
  feedDescription_ = std::move(text);
  markModified();
}

}  // namespace reamsim
