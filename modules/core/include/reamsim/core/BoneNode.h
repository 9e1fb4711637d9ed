#pragma once
// The bone being reamed: its undoable state history (the current state is what collision and cutting
// use), plus what import produced: the original, unrepaired mesh for display and the repair report.
#include <memory>
#include <string>

#include "reamsim/core/BoneHistory.h"
#include "reamsim/core/Node.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

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

 private:
  BoneHistory history_;
  std::shared_ptr<const TriangleMesh> originalMesh_;
  std::string importReport_;
};

}  // namespace reamsim
