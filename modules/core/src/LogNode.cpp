#include "reamsim/core/LogNode.h"

namespace reamsim {

void LogNode::append(CutLogEntry entry) {
  entries_.push_back(std::move(entry));
  markModified();
}

void LogNode::setNote(std::size_t row, std::string note) {
  if (entries_.at(row).note == note) return;
  entries_[row].note = std::move(note);
  ++notesRevision_;
  markModified();
}

}  // namespace reamsim
