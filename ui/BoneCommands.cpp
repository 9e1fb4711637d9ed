#include "BoneCommands.h"

#include "ReamSession.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/PlanNode.h"

namespace reamsim::ui {

ReplaceBoneCommand::ReplaceBoneCommand(ReamSession& session, BoneContent incoming, bool cuttable, const QString& text)
    : session_(session), other_(std::move(incoming)), otherCuttable_(cuttable) {
  setText(text);
}

void ReplaceBoneCommand::exchange() {
  PlanNode* plan = session_.plan();
  std::vector<Pose> poses = plan->poses();
  std::optional<std::string> feed = plan->feedDescription();
  {
    Document::BatchScope batch(session_.document());
    plan->setPoses(std::move(otherPoses_));
    plan->setFeedDescription(std::move(otherFeed_));
  }
  otherPoses_ = std::move(poses);
  otherFeed_ = std::move(feed);
  session_.exchangeBone(other_, otherCuttable_);
}

OtherBonesCommand::OtherBonesCommand(Document& document, std::vector<std::unique_ptr<BoneNode>> nodes,
                                     const QString& text)
    : document_(document), add_(true), detached_(std::move(nodes)) {
  setText(text);
}

OtherBonesCommand::OtherBonesCommand(Document& document, const std::vector<NodeId>& ids, const QString& text)
    : document_(document), add_(false), attached_(ids) {
  setText(text);
}

void OtherBonesCommand::attach() {
  Document::BatchScope batch(document_);
  for (auto& node : detached_) attached_.push_back(document_.add(std::move(node)).id());
  detached_.clear();
}

void OtherBonesCommand::detach() {
  Document::BatchScope batch(document_);
  for (NodeId id : attached_) {
    if (!document_.findAs<BoneNode>(id)) continue;  // only bones are handled here
    std::unique_ptr<Node> node = document_.remove(id);
    detached_.emplace_back(static_cast<BoneNode*>(node.release()));
  }
  attached_.clear();
}

}  // namespace reamsim::ui
