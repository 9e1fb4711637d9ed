// BoneState::commitByDiff: turns "here is the whole new mesh" into a MeshDelta against the previous
// state, so engines that cannot report local edits still get structural sharing.
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "reamsim/core/BoneState.h"

namespace reamsim {

namespace {

// Combines then finalises (murmur3 fmix64): the table masks low bits, and the low mantissa bits of
// round coordinates are all zero, so every input bit must reach them.
std::uint64_t mix(std::uint64_t h, std::uint64_t v) { return (h ^ v) * 0x9e3779b97f4a7c15ULL + (h >> 29); }
std::uint64_t finish(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

// Exact coordinates; +0.0 and -0.0 compare equal as doubles, so they must hash equal too.
struct CoordKey {
  std::uint64_t bits[3] = {};
  CoordKey() = default;
  explicit CoordKey(const Vec3& p) {
    for (int i = 0; i < 3; ++i) {
      const double d = p[i] == 0.0 ? 0.0 : p[i];
      std::memcpy(&bits[i], &d, sizeof d);
    }
  }
  bool operator==(const CoordKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};
struct CoordHash {
  std::size_t operator()(const CoordKey& k) const { return finish(mix(mix(mix(0, k.bits[0]), k.bits[1]), k.bits[2])); }
};

// Vertex-slot triple rotated so the smallest slot comes first: same triangle, same orientation.
struct TriKey {
  Triangle v{};
  TriKey() = default;
  explicit TriKey(const Triangle& t) {
    // Lexicographically smallest rotation (also well defined for degenerate, repeated-slot triangles).
    v = std::min({t, Triangle{t[1], t[2], t[0]}, Triangle{t[2], t[0], t[1]}});
  }
  bool operator==(const TriKey& o) const { return v == o.v; }
};
struct TriHash {
  std::size_t operator()(const TriKey& k) const { return finish(mix(mix(mix(0, k.v[0]), k.v[1]), k.v[2])); }
};

// Multimap key -> slots as an open-addressing table of "head slot per key" plus "next slot with the
// same key", so duplicates (coincident vertices, repeated triangles) are each claimed once, lowest slot
// first. Open addressing because node-based maps made the diff of a 1M-triangle mesh 3x slower.
template <class Key, class Hash>
class SlotPool {
 public:
  SlotPool(std::size_t slotCount, std::size_t keyCount) : next_(slotCount, BoneState::kBadSlot) {
    std::size_t capacity = 16;
    while (capacity < 2 * keyCount) capacity *= 2;
    entries_.resize(capacity);
    mask_ = capacity - 1;
  }
  // Slots must arrive in descending order so the lowest ends up at the head.
  void addInDescendingOrder(const Key& key, std::uint32_t slot) {
    Entry& e = probe(key);
    if (!e.used) {
      e = {key, slot, true};
    } else {
      next_[slot] = e.head;
      e.head = slot;
    }
  }
  std::uint32_t claim(const Key& key) {
    Entry& e = probe(key);
    if (!e.used || e.head == BoneState::kBadSlot) return BoneState::kBadSlot;
    const std::uint32_t slot = e.head;
    e.head = next_[slot];  // an exhausted key keeps its entry so probe sequences stay intact
    return slot;
  }

 private:
  struct Entry {
    Key key{};
    std::uint32_t head = BoneState::kBadSlot;
    bool used = false;
  };
  Entry& probe(const Key& key) {
    for (std::size_t i = Hash{}(key) & mask_;; i = (i + 1) & mask_)
      if (!entries_[i].used || entries_[i].key == key) return entries_[i];
  }
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> next_;
  std::size_t mask_ = 0;
};

}  // namespace

BoneState BoneState::commitByDiff(const BoneState& prev, const TriangleMesh& next) {
  const std::size_t nv = next.vertices.size();
  for (const Triangle& t : next.triangles)
    for (std::uint32_t v : t)
      if (v >= nv) throw std::invalid_argument("BoneState::commitByDiff: vertex index " + std::to_string(v) + " out of range");
  if (nv >= MeshDelta::kNewVertexBit) throw std::invalid_argument("BoneState::commitByDiff: too many vertices");

  MeshDelta delta;
  std::vector<std::uint32_t> ref(nv);
  {
    SlotPool<CoordKey, CoordHash> pool(prev.vertexSlotCount(), prev.liveVertexCount());
    for (std::uint32_t s = static_cast<std::uint32_t>(prev.vertexSlotCount()); s-- > 0;)
      if (prev.isVertexLive(s)) pool.addInDescendingOrder(CoordKey(prev.vertex(s)), s);
    for (std::size_t i = 0; i < nv; ++i) {
      const std::uint32_t slot = pool.claim(CoordKey(next.vertices[i]));
      if (slot != kBadSlot) {
        ref[i] = slot;
      } else {
        ref[i] = MeshDelta::newVertex(static_cast<std::uint32_t>(delta.addedVertices.size()));
        delta.addedVertices.push_back(next.vertices[i]);
      }
    }
  }

  std::vector<char> kept(prev.triangleSlotCount(), 0);
  {
    SlotPool<TriKey, TriHash> pool(prev.triangleSlotCount(), prev.liveTriangleCount());
    for (std::uint32_t s = static_cast<std::uint32_t>(prev.triangleSlotCount()); s-- > 0;)
      if (prev.isTriangleLive(s)) pool.addInDescendingOrder(TriKey(prev.triangle(s)), s);
    for (const Triangle& t : next.triangles) {
      const Triangle mapped{ref[t[0]], ref[t[1]], ref[t[2]]};
      const bool allExisting = !MeshDelta::isNewVertex(mapped[0]) && !MeshDelta::isNewVertex(mapped[1]) &&
                               !MeshDelta::isNewVertex(mapped[2]);
      const std::uint32_t slot = allExisting ? pool.claim(TriKey(mapped)) : kBadSlot;
      if (slot != kBadSlot) {
        kept[slot] = 1;
      } else {
        delta.addedTriangles.push_back(mapped);
      }
    }
  }
  for (std::uint32_t s = 0; s < prev.triangleSlotCount(); ++s)
    if (prev.isTriangleLive(s) && !kept[s]) delta.removedTriangles.push_back(s);

  if (delta.removedTriangles.empty() && delta.addedTriangles.empty()) return prev;  // share everything
  return prev.applyDelta(delta);
}

SlotChanges BoneState::changedTriangleSlots(const BoneState& prev, const BoneState& next) {
  SlotChanges out;
  const std::size_t slots = std::max(prev.triangles_.size(), next.triangles_.size());
  for (std::size_t first = 0; first < slots; first += kChunkSize) {
    const std::size_t c = first / kChunkSize;
    const bool inBoth = first < prev.triangles_.size() && first < next.triangles_.size();
    // A shared chunk (same storage) holds the same triangles, unless one state has since grown into it.
    const std::size_t last = std::min(slots, first + kChunkSize);
    if (inBoth && prev.triangles_.chunkIdentity(c) == next.triangles_.chunkIdentity(c) &&
        last <= std::min(prev.triangles_.size(), next.triangles_.size()))
      continue;
    for (std::size_t s = first; s < last; ++s) {
      const auto slot = std::uint32_t(s);
      const bool wasLive = prev.isTriangleLive(slot), isLive = next.isTriangleLive(slot);
      // The same corner slots are the same triangle unless a corner's slot was freed and taken again by a new
      // vertex in between (one applyDelta can do both, and put the triangle back in the slot it left).
      if (wasLive && isLive && prev.triangles_[s] == next.triangles_[s]) {
        const Triangle& t = next.triangles_[s];
        if (prev.vertices_[t[0]] == next.vertices_[t[0]] && prev.vertices_[t[1]] == next.vertices_[t[1]] &&
            prev.vertices_[t[2]] == next.vertices_[t[2]])
          continue;
      }
      if (wasLive) out.removed.push_back(slot);
      if (isLive) out.added.push_back(slot);
    }
  }
  return out;
}

}  // namespace reamsim
