#pragma once
// Append-only cut log. Undo does not erase rows: the log records what was done, and each row names
// the bone revision it produced (CutLogEntry::boneStateId). A row's note is the one thing that may change
// after it is appended: an annotation, not a record of the step.
#include <vector>

#include "reamsim/core/CutLogEntry.h"
#include "reamsim/core/Node.h"

namespace reamsim {

class LogNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Log;
  explicit LogNode(std::string name = {}) : Node(std::move(name)) {}
  NodeKind kind() const override { return kKind; }

  void append(CutLogEntry entry);
  const std::vector<CutLogEntry>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  const CutLogEntry& last() const { return entries_.back(); }  // precondition: !empty()
  // Sets row `row`'s note (precondition: row < size()); reports Modified when it changes.
  void setNote(std::size_t row, std::string note);
  // Counts the notes' changes: a window compares it with the count at its last save (unsaved annotations).
  std::uint64_t notesRevision() const { return notesRevision_; }
  double cumulativeMm3() const { return entries_.empty() ? 0.0 : entries_.back().cumulativeMm3; }

 private:
  std::vector<CutLogEntry> entries_;
  std::uint64_t notesRevision_ = 0;
};

}  // namespace reamsim
