#include "reamsim/core/BoneNode.h"

namespace reamsim {

void BoneNode::resetHistory(BoneState initial, std::string label) {
  history_.reset(std::move(initial), std::move(label));
  markModified();
}

std::uint64_t BoneNode::commit(BoneState state, std::string label) {
  const std::uint64_t revision = history_.commit(std::move(state), std::move(label));
  markModified();
  return revision;
}

bool BoneNode::undo() {
  if (!history_.undo()) return false;
  markModified();
  return true;
}

bool BoneNode::redo() {
  if (!history_.redo()) return false;
  markModified();
  return true;
}

void BoneNode::setOriginalMesh(std::shared_ptr<const TriangleMesh> mesh) {
  originalMesh_ = std::move(mesh);
  markModified();
}

void BoneNode::setImportReport(std::string text) {
  importReport_ = std::move(text);
  markModified();
}

void BoneNode::setLandmarks(const ScapulaLandmarks& landmarks) {
  if (landmarks == landmarks_) return;
  landmarks_ = landmarks;
  markModified();
}

void BoneNode::setLandmark(ScapulaLandmark which, const std::optional<Vec3>& point) {
  ScapulaLandmarks next = landmarks_;
  next[which] = point;
  setLandmarks(next);
}

void BoneNode::setLandmarkSide(BodySide side) {
  ScapulaLandmarks next = landmarks_;
  next.side = side;
  setLandmarks(next);
}

void BoneNode::setPlannedAxis(const std::optional<Pose>& axis) {
  const bool same = axis.has_value() == plannedAxis_.has_value() &&
                    (!axis || (axis->tip == plannedAxis_->tip && axis->axis == plannedAxis_->axis &&
                               axis->rollDeg == plannedAxis_->rollDeg));
  if (same) return;
  plannedAxis_ = axis;
  markModified();
}

void BoneNode::setPatientFrame(PatientFrame frame) {
  if (frame == patientFrame_) return;
  patientFrame_ = frame;
  markModified();
}

void BoneNode::setSource(std::string text) {
  if (text == source_) return;
  source_ = std::move(text);
  markModified();
}

void BoneNode::setCuttable(bool cuttable) {
  if (cuttable == cuttable_) return;
  cuttable_ = cuttable;
  markModified();
}

void BoneNode::swapContent(BoneContent& other) {
  std::string name = this->name();
  std::swap(history_, other.history);
  std::swap(originalMesh_, other.originalMesh);
  std::swap(importReport_, other.importReport);
  std::swap(patientFrame_, other.patientFrame);
  std::swap(source_, other.source);
  std::swap(landmarks_, other.landmarks);
  std::swap(plannedAxis_, other.plannedAxis);
  std::swap(cuttable_, other.cuttable);
  setName(std::move(other.name));  // marks the node modified (batched with the rest by the caller)
  other.name = std::move(name);
  markModified();
}

}  // namespace reamsim
