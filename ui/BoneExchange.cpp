// ReamSession::exchangeBone: the session's half of the undoable bone replacement (CT import). Kept out of
// ReamSession.cpp so that the reaming loop's file stays about the loop.
#include "ReamSession.h"

namespace reamsim::ui {

void ReamSession::exchangeBone(BoneContent& other) {
  const QuietPlanning quiet(*this);  // the landmarks go with their bone: not an edit
  cancelQueued();
  cancelPreview();  // asked of the bone that goes
  if (running_) watcher_.waitForFinished();  // its result is dropped: revisions never repeat (BoneHistory)
  {
    Document::BatchScope batch(document_);
    bone_->swapContent(other);
    alerts_->clear();
    interaction_->setPlaceRequest(std::nullopt);  // asked for on the bone that leaves
  }
  // As loadBone: the log's cumulative volume is measured against the bone as it was imported.
  initialVolume_ = bone_->history().entries().front().state.volume();
  lastComputedPose_.reset();
  lastMinDistance_ = std::numeric_limits<double>::infinity();
  rebuildEngine();
  Q_EMIT boneReplaced();
}

void ReamSession::adoptHistory(BoneHistory history) {
  const QuietPlanning quiet(*this);  // outlives the batch, whose report comes at its end
  Document::BatchScope batch(document_);  // the views never see the bone emptied between the two swaps
  BoneContent content;
  bone_->swapContent(content);
  content.history = std::move(history);
  exchangeBone(content);
}

std::optional<Pose> ReamSession::settledReamerPose() const {
  // A running step has moved lastComputedPose_ to where it goes; a running contact search moves nothing.
  return running_ && control_ ? poseBeforeRunning_ : lastComputedPose_;
}

void ReamSession::returnReamerTo(const Pose& pose) {
  cancelQueued();
  reamer_->setPose(pose);
  lastComputedPose_ = pose;
}

}  // namespace reamsim::ui
