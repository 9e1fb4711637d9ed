#include "reamsim/core/BoneHistory.h"

#include <atomic>

namespace reamsim {
namespace {

std::uint64_t newRevision() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

BoneHistory::BoneHistory(BoneState initial, std::string label) { reset(std::move(initial), std::move(label)); }

void BoneHistory::reset(BoneState initial, std::string label) {
  entries_.clear();
  entries_.push_back({std::move(initial), std::move(label), newRevision()});
  cursor_ = 0;
}

std::uint64_t BoneHistory::commit(BoneState state, std::string label) {
  entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(cursor_) + 1, entries_.end());
  entries_.push_back({std::move(state), std::move(label), newRevision()});
  cursor_ = entries_.size() - 1;
  return entries_.back().revision;
}

bool BoneHistory::undo() {
  if (!canUndo()) return false;
  --cursor_;
  return true;
}

bool BoneHistory::redo() {
  if (!canRedo()) return false;
  ++cursor_;
  return true;
}

const BoneHistory::Entry* BoneHistory::find(std::uint64_t revision) const {
  for (const Entry& e : entries_)
    if (e.revision == revision) return &e;
  return nullptr;
}

StorageStats BoneHistory::storageStats() const {
  std::vector<const BoneState*> states;
  states.reserve(entries_.size());
  for (const Entry& e : entries_) states.push_back(&e.state);
  return measureStorage(states);
}

}  // namespace reamsim
