#include "BoneCommands.h"

#include <utility>

#include "BonePlacement.h"
#include "ReamSession.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/PlanNode.h"

namespace reamsim::ui {

void CutBoneCompanions::exchange(ReamSession& session, const std::function<void()>& exchangeBone) {
  PlanNode& plan = *session.plan();
  std::vector<Pose> poses = plan.poses();
  std::optional<std::string> feed = plan.feedDescription();
  {
    Document::BatchScope batch(*plan.document());
    plan.setPoses(std::move(poses_));
    plan.setFeedDescription(std::move(feed_));
  }
  poses_ = std::move(poses);
  feed_ = std::move(feed);
  // The reamer's pose: undo and redo put it back where it was last computed on the incoming bone (often seated in
  // that bone's own cut); a pose from the other bone could bury it in this one, and the next move would cut all it
  // overlaps. Where no step had been computed on the incoming bone, the reamer goes clear of it. The outgoing
  // bone's pose is taken before exchangeBone drops the moves not computed yet.
  const std::optional<Pose> leaving = session.settledReamerPose();
  exchangeBone();
  const bool first = std::exchange(first_, false);
  if (reamerPose_)
    session.returnReamerTo(*reamerPose_);
  else if (!first)
    session.moveReamer(startPoseFor(session.bone()->current().bounds()));
  reamerPose_ = leaving;
}

BoneContent boneContentFrom(ImportedBone bone, std::string name, std::string label) {
  BoneContent content;
  content.name = std::move(name);
  content.history = BoneHistory(BoneState::fromMesh(bone.mesh), std::move(label));
  content.originalMesh = std::move(bone.original);
  content.importReport = std::move(bone.report);
  content.patientFrame = bone.frame;
  content.source = std::move(bone.source);
  content.cuttable = bone.cuttable;
  return content;
}

ReplaceBoneCommand::ReplaceBoneCommand(ReamSession& session, BoneContent incoming, const QString& text)
    : session_(session), other_(std::move(incoming)) {
  setText(text);
}

void ReplaceBoneCommand::exchange() {
  others_.exchange(session_, [this] { session_.exchangeBone(other_); });
}

SwapBoneBesideCommand::SwapBoneBesideCommand(ReamSession& session, NodeId beside, const QString& text)
    : session_(session), beside_(beside) {
  setText(text);
}

void SwapBoneBesideCommand::exchange() {
  BoneNode* beside = session_.document().findAs<BoneNode>(beside_);
  // Always there while this command is on the stack: a later removal is undone before this command is, and a
  // node put back keeps its id (Document::add).
  if (!beside) return;
  // One batch: the views see the two bones swapped, never the bone beside emptied half way.
  Document::BatchScope batch(session_.document());
  BoneContent content;
  beside->swapContent(content);
  // Whatever happens below (an engine that cannot be built for lack of memory), the bone in `content` goes
  // back into a node: no bone is lost with this local.
  struct PutBack {
    BoneNode& node;
    BoneContent& content;
    ~PutBack() { node.swapContent(content); }
  } putBack{*beside, content};
  // The session's bone takes the one beside, `content` the cut bone.
  others_.exchange(session_, [this, &content] { session_.exchangeBone(content); });
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
