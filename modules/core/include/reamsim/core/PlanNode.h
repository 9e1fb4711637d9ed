#pragma once
// A reaming plan: which reamer (by spec name) and the sequence of poses to visit.
#include <optional>
#include <string>
#include <vector>

#include "reamsim/core/Node.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

class PlanNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Plan;
  explicit PlanNode(std::string name = {}) : Node(std::move(name)) {}
  NodeKind kind() const override { return kKind; }

  const std::string& reamerSpecName() const { return reamerSpecName_; }
  void setReamerSpecName(std::string name);

  const std::vector<Pose>& poses() const { return poses_; }
  void setPoses(std::vector<Pose> poses);
  void addPose(const Pose& pose);

  // Free text such as "feed 0.5 mm/step to 3 mm"; nullopt when the plan is a plain pose list.
  const std::optional<std::string>& feedDescription() const { return feedDescription_; }
  void setFeedDescription(std::optional<std::string> text);

 private:
  std::string reamerSpecName_;
  std::vector<Pose> poses_;
  std::optional<std::string> feedDescription_;
};

}  // namespace reamsim
