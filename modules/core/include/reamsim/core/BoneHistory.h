#pragma once
// Linear undo/redo history of bone states. States share storage (see BoneState), so keeping every
// committed cut costs roughly the size of the edits, not of the mesh.
// Revisions come from one process-wide counter: a bone node whose whole history is swapped for another
// (BoneNode::swapContent, undoable CT import) never shows a revision that a cache keyed by revision
// (engine, view) has seen for a different state.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "reamsim/core/BoneState.h"

namespace reamsim {

class BoneHistory {
 public:
  struct Entry {
    BoneState state;
    std::string label;
    std::uint64_t revision;  // unique in the process (across histories), increasing, never reused
  };

  explicit BoneHistory(BoneState initial = {}, std::string label = "initial");

  const BoneState& current() const { return entries_[cursor_].state; }
  const Entry& currentEntry() const { return entries_[cursor_]; }
  std::uint64_t currentRevision() const { return entries_[cursor_].revision; }

  // Appends after the cursor and moves there; states after the cursor (the redo branch) are dropped.
  std::uint64_t commit(BoneState state, std::string label);
  bool canUndo() const { return cursor_ > 0; }
  bool canRedo() const { return cursor_ + 1 < entries_.size(); }
  bool undo();  // false when there is nothing to undo
  bool redo();
  void reset(BoneState initial, std::string label = "initial");  // forget everything

  const std::vector<Entry>& entries() const { return entries_; }
  std::size_t cursor() const { return cursor_; }
  std::size_t size() const { return entries_.size(); }
  // Entry with this revision, or nullptr (e.g. dropped with a redo branch).
  const Entry* find(std::uint64_t revision) const;

  StorageStats storageStats() const;
  std::size_t uniqueBytes() const { return storageStats().uniqueBytes; }
  std::size_t sharedBytes() const { return storageStats().sharedBytes; }

 private:
  std::vector<Entry> entries_;
  std::size_t cursor_ = 0;
};

}  // namespace reamsim
