#pragma once
// Append-only cut log. Undo does not erase rows: the log records what was done, and each row names
// the bone revision it produced (CutLogEntry::boneStateId).
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
  double cumulativeMm3() const { return entries_.empty() ? 0.0 : entries_.back().cumulativeMm3; }

 private:
  std::vector<CutLogEntry> entries_;
};

}  // namespace reamsim
