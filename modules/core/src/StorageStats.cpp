#include <unordered_map>

#include "reamsim/core/BoneState.h"

namespace reamsim {

std::size_t BoneState::storageBytes() const {
  std::size_t bytes = 0;
  visitStorage([&](const void*, std::size_t b) { bytes += b; });
  return bytes;
}

StorageStats measureStorage(const std::vector<const BoneState*>& states) {
  struct Block {
    std::size_t bytes;
    std::size_t users;      // states referencing the block
    std::size_t lastState;  // to count a state once even if it saw the block twice
  };
  std::unordered_map<const void*, Block> blocks;
  StorageStats stats;
  for (std::size_t s = 0; s < states.size(); ++s) {
    states[s]->visitStorage([&](const void* id, std::size_t bytes) {
      stats.logicalBytes += bytes;
      auto [it, inserted] = blocks.try_emplace(id, Block{bytes, 1, s});
      if (!inserted && it->second.lastState != s) {
        ++it->second.users;
        it->second.lastState = s;
      }
    });
  }
  for (const auto& [id, block] : blocks) {
    stats.uniqueBytes += block.bytes;
    if (block.users > 1) stats.sharedBytes += block.bytes;
  }
  return stats;
}

}  // namespace reamsim
