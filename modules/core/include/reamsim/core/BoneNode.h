#pragma once
// The bone being reamed: its undoable state history (the current state is what collision and cutting
// use), plus what import produced: the original, unrepaired mesh for display, the repair report, where
// the bone came from and the patient coordinate convention its coordinates are in.
#include <memory>
#include <optional>
#include <string>

#include "reamsim/core/BoneHistory.h"
#include "reamsim/core/ScapulaLandmarks.h"
#include "reamsim/core/Node.h"
#include "reamsim/core/PatientFrame.h"
#include "reamsim/core/Pose.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Everything a bone is, as one value. BoneNode::swapContent exchanges it with a node's own, so an undo
// command can take a whole bone out of the document and put it back exactly (history and cursor
// included) without copying meshes: the states share storage.
struct BoneContent {
  std::string name;
  BoneHistory history;
  std::shared_ptr<const TriangleMesh> originalMesh;
  std::string importReport;
  PatientFrame patientFrame = PatientFrame::Unspecified;
  std::string source;
  bool cuttable = false;  // a clean closed solid the engine may cut (else shown, with collision alerts only)
  ScapulaLandmarks landmarks;  // placed on this bone, in its coordinates (docs/PLANNING.md)
  std::optional<Pose> plannedAxis;  // the reaming axis planned on it (docs/PLANNING.md)
};

class BoneNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Bone;
  explicit BoneNode(std::string name = {}, BoneState initial = {}) : Node(std::move(name)), history_(std::move(initial)) {}
  NodeKind kind() const override { return kKind; }

  const BoneHistory& history() const { return history_; }
  const BoneState& current() const { return history_.current(); }
  std::uint64_t currentRevision() const { return history_.currentRevision(); }

  // Each of these reports a modification when it changes the current state.
  void resetHistory(BoneState initial, std::string label = "initial");
  std::uint64_t commit(BoneState state, std::string label);  // returns the new revision
  bool undo();
  bool redo();

  const std::shared_ptr<const TriangleMesh>& originalMesh() const { return originalMesh_; }
  void setOriginalMesh(std::shared_ptr<const TriangleMesh> mesh);
  const std::string& importReport() const { return importReport_; }
  void setImportReport(std::string text);

  // The convention of the coordinates (LPS, RAS, or unspecified for a mesh that names none).
  PatientFrame patientFrame() const { return patientFrame_; }
  void setPatientFrame(PatientFrame frame);
  // Where the bone came from, in words: "CT volume /data/head.nrrd", a mesh file path, "bundled default scapula".
  const std::string& source() const { return source_; }
  void setSource(std::string text);
  // The scapular landmarks placed on this bone (none placed: all unset, side unspecified).
  const ScapulaLandmarks& landmarks() const { return landmarks_; }
  void setLandmarks(const ScapulaLandmarks& landmarks);
  void setLandmark(ScapulaLandmark which, const std::optional<Vec3>& point);
  void setLandmarkSide(BodySide side);
  // The reaming axis planned on this bone: `tip` the glenoid centre it passes through, `axis` the feed
  // direction (into the bone). Set by the Planning dock's Aim; nullopt when none is planned.
  const std::optional<Pose>& plannedAxis() const { return plannedAxis_; }
  void setPlannedAxis(const std::optional<Pose>& axis);
  // Whether the engine may cut it: set by whoever imported it, from the import's validation (closed,
  // outward, free of self-intersections and degenerate faces). A bone that is not is shown, not cut.
  bool cuttable() const { return cuttable_; }
  void setCuttable(bool cuttable);

  // Exchanges name, history, original mesh, report, frame, source, landmarks, planned axis and cuttability with `other` (reported
  // as modified; wrap in a Document::BatchScope for a single notification).
  void swapContent(BoneContent& other);

 private:
  BoneHistory history_;
  std::shared_ptr<const TriangleMesh> originalMesh_;
  std::string importReport_;
  PatientFrame patientFrame_ = PatientFrame::Unspecified;
  std::string source_;
  ScapulaLandmarks landmarks_;
  std::optional<Pose> plannedAxis_;
  bool cuttable_ = false;
};

}  // namespace reamsim
