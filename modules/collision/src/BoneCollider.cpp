#include "reamsim/collision/BoneCollider.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

namespace reamsim {

namespace {

BvhTriangle cornersOf(const BoneState& s, std::uint32_t slot) {
  const Triangle& t = s.triangle(slot);
  return {s.vertex(t[0]), s.vertex(t[1]), s.vertex(t[2])};
}

bool sameTriangle(const BvhTriangle& x, const BvhTriangle& y) { return x.a == y.a && x.b == y.b && x.c == y.c; }

bool closedFromEdges(std::vector<std::uint64_t>& directed) {
  std::sort(directed.begin(), directed.end());
  for (std::size_t i = 1; i < directed.size(); ++i)
    if (directed[i] == directed[i - 1]) return false;  // an edge used twice in the same direction
  for (std::uint64_t e : directed) {
    const std::uint64_t reversed = (e << 32) | (e >> 32);
    if (!std::binary_search(directed.begin(), directed.end(), reversed)) return false;
  }
  return !directed.empty();
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

}  // namespace

bool isClosedSurface(const TriangleMesh& mesh) {
  std::vector<std::uint64_t> directed;
  directed.reserve(mesh.triangles.size() * 3);
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) directed.push_back(edgeKey(t[k], t[(k + 1) % 3]));
  return closedFromEdges(directed);
}

SlotChanges diffSlots(const TriangleBvh& bvh, const BoneState& next) {
  SlotChanges out;
  const std::size_t n = std::max(bvh.slotCapacity(), next.triangleSlotCount());
  for (std::uint32_t s = 0; s < n; ++s) {
    const bool inTree = bvh.contains(s);
    const bool live = next.isTriangleLive(s);
    if (inTree && live) {
      if (!sameTriangle(bvh.triangle(s), cornersOf(next, s))) {
        out.removed.push_back(s);
        out.added.push_back(s);
      }
    } else if (inTree) {
      out.removed.push_back(s);
    } else if (live) {
      out.added.push_back(s);
    }
  }
  return out;
}

BoneCollider::BoneCollider(const BoneState& state) : followed_(state) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::uint32_t> slots;
  std::vector<BvhTriangle> tris;
  std::vector<std::uint64_t> directed;
  slots.reserve(state.liveTriangleCount());
  tris.reserve(state.liveTriangleCount());
  directed.reserve(3 * state.liveTriangleCount());
  state.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    slots.push_back(slot);
    tris.push_back({state.vertex(t[0]), state.vertex(t[1]), state.vertex(t[2])});
    for (int k = 0; k < 3; ++k) directed.push_back(edgeKey(t[k], t[(k + 1) % 3]));
  });
  bvh_ = TriangleBvh::fromTriangles(slots, tris);
  buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  closed_ = closedFromEdges(directed);
}

BoneCollider::BoneCollider(const TriangleMesh& mesh) {
  const auto start = std::chrono::steady_clock::now();
  bvh_ = TriangleBvh::fromMesh(mesh);
  buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  closed_ = isClosedSurface(mesh);
}

BvhUpdateStats BoneCollider::update(const BoneState& next, const std::vector<std::uint32_t>& removedSlots,
                                    const std::vector<std::uint32_t>& addedSlots) {
  std::vector<BvhTriangle> tris;
  tris.reserve(addedSlots.size());
  for (std::uint32_t s : addedSlots) {
    if (!next.isTriangleLive(s))
      throw std::invalid_argument("BoneCollider::update: added slot " + std::to_string(s) + " is not live in the new state");
    tris.push_back(cornersOf(next, s));
  }
  BvhUpdateStats stats = bvh_.update(removedSlots, addedSlots, tris);
  followed_ = next;
  return stats;
}

BvhUpdateStats BoneCollider::applyDelta(const BoneState& next, const MeshDelta& delta, const DeltaPlacement& placement) {
  if (placement.triangleSlots.size() != delta.addedTriangles.size())
    throw std::invalid_argument("BoneCollider::applyDelta: placement does not match the delta");
  return update(next, delta.removedTriangles, placement.triangleSlots);
}

BvhUpdateStats BoneCollider::syncTo(const BoneState& next) {
  const auto start = std::chrono::steady_clock::now();
  const SlotChanges c = changesTo(next);
  BvhUpdateStats stats = update(next, c.removed, c.added);
  stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

SlotChanges BoneCollider::changesTo(const BoneState& next) const {
  return followed_ ? BoneState::changedTriangleSlots(*followed_, next) : diffSlots(bvh_, next);
}

}  // namespace reamsim
