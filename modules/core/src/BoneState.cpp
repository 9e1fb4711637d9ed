#include "reamsim/core/BoneState.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace reamsim {

namespace {

constexpr Triangle kTombstone{BoneState::kBadSlot, BoneState::kBadSlot, BoneState::kBadSlot};

// Spreads the low 21 bits of v so that two zero bits separate each (for 3D Morton codes).
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

struct MortonCoder {
  Vec3 origin;
  Vec3 scale;
  explicit MortonCoder(const Bounds& b) : origin(b.min) {
    const Vec3 s = b.size();
    constexpr double kMax = 2097151.0;  // 2^21 - 1
    scale = {s.x > 0 ? kMax / s.x : 0, s.y > 0 ? kMax / s.y : 0, s.z > 0 ? kMax / s.z : 0};
  }
  std::uint64_t operator()(const Vec3& p) const {
    auto q = [](double v) { return static_cast<std::uint64_t>(std::clamp(v, 0.0, 2097151.0)); };
    return spreadBits(q((p.x - origin.x) * scale.x)) | spreadBits(q((p.y - origin.y) * scale.y)) << 1 |
           spreadBits(q((p.z - origin.z) * scale.z)) << 2;
  }
};

// Indices 0..n-1 stably sorted by key, so equal keys keep their input order (deterministic).
std::vector<std::uint32_t> orderBy(const std::vector<std::uint64_t>& keys) {
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  return order;
}

[[noreturn]] void invalid(const std::string& what) { throw std::invalid_argument("BoneState: " + what); }

bool onBoundary(const Vec3& p, const Bounds& b) {
  return p.x == b.min.x || p.x == b.max.x || p.y == b.min.y || p.y == b.max.y || p.z == b.min.z || p.z == b.max.z;
}

}  // namespace

BoneState BoneState::fromMesh(const TriangleMesh& mesh, Ordering ordering, const std::optional<Vec3>& volumeOrigin) {
  const std::size_t nv = mesh.vertices.size();
  if (nv >= MeshDelta::kNewVertexBit) invalid("too many vertices");
  std::vector<std::uint32_t> uses(nv, 0);
  for (const Vec3& p : mesh.vertices)
    if (!isFinite(p)) invalid("non-finite vertex coordinate");
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) {
      if (v >= nv) invalid("triangle references vertex " + std::to_string(v) + " of " + std::to_string(nv));
      ++uses[v];
    }

  std::vector<std::uint32_t> vertexOrder(nv), triangleOrder(mesh.triangles.size());
  std::iota(vertexOrder.begin(), vertexOrder.end(), 0u);
  std::iota(triangleOrder.begin(), triangleOrder.end(), 0u);
  const Bounds inputBounds = computeBounds(mesh);
  if (ordering == Ordering::Spatial && !inputBounds.empty()) {
    const MortonCoder code(inputBounds);
    std::vector<std::uint64_t> keys(nv);
    for (std::size_t i = 0; i < nv; ++i) keys[i] = code(mesh.vertices[i]);
    vertexOrder = orderBy(keys);
    keys.resize(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const Triangle& t = mesh.triangles[i];
      keys[i] = code((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0);
    }
    triangleOrder = orderBy(keys);
  }

  BoneState s;
  if (volumeOrigin && !isFinite(*volumeOrigin)) invalid("non-finite volume origin");
  s.volumeOrigin_ = volumeOrigin ? *volumeOrigin : inputBounds.empty() ? Vec3{} : inputBounds.center();
  std::vector<std::uint32_t> slotOf(nv);
  for (std::uint32_t slot = 0; slot < nv; ++slot) {
    const std::uint32_t v = vertexOrder[slot];
    slotOf[v] = slot;
    s.vertices_.push_back(mesh.vertices[v]);
    s.useCounts_.push_back(uses[v]);
    if (uses[v] > 0) ++s.liveVertices_;
  }
  for (std::uint32_t slot = static_cast<std::uint32_t>(nv); slot-- > 0;)
    if (s.useCounts_[slot] == 0) s.freeVertices_.push_back(slot);  // lowest slot on top
  for (std::uint32_t i : triangleOrder) {
    const Triangle& t = mesh.triangles[i];
    const Triangle mapped{slotOf[t[0]], slotOf[t[1]], slotOf[t[2]]};
    s.triangles_.push_back(mapped);
    s.volume6_ += s.volumeTerm(mapped);
  }
  s.liveTriangles_ = mesh.triangles.size();
  s.recomputeBounds();
  return s;
}

TriangleMesh BoneState::toMesh() const {
  TriangleMesh mesh;
  mesh.vertices.reserve(liveVertices_);
  mesh.triangles.reserve(liveTriangles_);
  std::vector<std::uint32_t> compact(vertices_.size(), kBadSlot);
  for (std::uint32_t slot = 0; slot < vertices_.size(); ++slot) {
    if (useCounts_[slot] == 0) continue;
    compact[slot] = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(vertices_[slot]);
  }
  forEachLiveTriangle([&](std::uint32_t, const Triangle& t) {
    mesh.triangles.push_back({compact[t[0]], compact[t[1]], compact[t[2]]});
  });
  return mesh;
}

double BoneState::volumeTerm(const Triangle& t) const {
  const Vec3 a = vertices_[t[0]] - volumeOrigin_, b = vertices_[t[1]] - volumeOrigin_,
             c = vertices_[t[2]] - volumeOrigin_;
  return dot(a, cross(b, c));
}

void BoneState::recomputeBounds() {
  bounds_ = Bounds{};
  for (std::uint32_t slot = 0; slot < vertices_.size(); ++slot)
    if (useCounts_[slot] > 0) bounds_.add(vertices_[slot]);
}

std::uint32_t BoneState::allocateVertex(const Vec3& p) {
  if (freeVertices_.empty()) {
    vertices_.push_back(p);
    useCounts_.push_back(0);
    return static_cast<std::uint32_t>(vertices_.size() - 1);
  }
  const std::uint32_t slot = freeVertices_.back();
  freeVertices_.pop_back();
  vertices_.set(slot, p);
  return slot;
}

std::uint32_t BoneState::allocateTriangle(const Triangle& t) {
  if (freeTriangles_.empty()) {
    triangles_.push_back(t);
    return static_cast<std::uint32_t>(triangles_.size() - 1);
  }
  const std::uint32_t slot = freeTriangles_.back();
  freeTriangles_.pop_back();
  triangles_.set(slot, t);
  return slot;
}

void BoneState::freeVertex(std::uint32_t slot, bool& boundsDirty) {
  freeVertices_.push_back(slot);
  --liveVertices_;
  // Removing an extreme vertex may shrink the box; only then is a full recompute needed.
  if (onBoundary(vertices_[slot], bounds_)) boundsDirty = true;
}

// Order matters: removed triangles free their slots first so added ones land in the same chunks;
// vertices kept by added triangles are pinned before orphans are freed, and orphans are freed before
// new vertices are allocated so those reuse the just-freed (nearby) slots.
BoneState BoneState::applyDelta(const MeshDelta& delta, DeltaPlacement* placement) const {
  for (const Vec3& p : delta.addedVertices)
    if (!isFinite(p)) invalid("delta adds a non-finite vertex");
  for (const Triangle& t : delta.addedTriangles)
    for (std::uint32_t ref : t) {
      if (MeshDelta::isNewVertex(ref) ? MeshDelta::newVertexIndex(ref) >= delta.addedVertices.size() : !isVertexLive(ref))
        invalid("delta triangle references invalid vertex " + std::to_string(ref));
    }
  if (vertices_.size() + delta.addedVertices.size() >= MeshDelta::kNewVertexBit) invalid("too many vertices");

  BoneState r = *this;
  bool boundsDirty = false;

  std::vector<std::uint32_t> orphans;
  for (std::uint32_t slot : delta.removedTriangles) {
    if (!r.isTriangleLive(slot)) invalid("removed triangle slot " + std::to_string(slot) + " is not live");
    const Triangle t = r.triangles_[slot];
    r.volume6_ -= r.volumeTerm(t);
    r.triangles_.set(slot, kTombstone);
    r.freeTriangles_.push_back(slot);
    --r.liveTriangles_;
    for (std::uint32_t v : t) {
      const std::uint32_t uses = r.useCounts_[v] - 1;
      r.useCounts_.set(v, uses);
      if (uses == 0) orphans.push_back(v);
    }
  }

  for (const Triangle& t : delta.addedTriangles)
    for (std::uint32_t ref : t)
      if (!MeshDelta::isNewVertex(ref)) r.useCounts_.set(ref, r.useCounts_[ref] + 1);

  for (std::uint32_t v : orphans)
    if (r.useCounts_[v] == 0) r.freeVertex(v, boundsDirty);

  std::vector<std::uint32_t> newSlots;
  newSlots.reserve(delta.addedVertices.size());
  for (const Vec3& p : delta.addedVertices) newSlots.push_back(r.allocateVertex(p));

  std::vector<std::uint32_t> triangleSlots;
  triangleSlots.reserve(delta.addedTriangles.size());
  for (const Triangle& t : delta.addedTriangles) {
    Triangle mapped = t;
    for (std::uint32_t& ref : mapped) {
      if (!MeshDelta::isNewVertex(ref)) continue;
      ref = newSlots[MeshDelta::newVertexIndex(ref)];
      r.useCounts_.set(ref, r.useCounts_[ref] + 1);
    }
    triangleSlots.push_back(r.allocateTriangle(mapped));
    r.volume6_ += r.volumeTerm(mapped);
    ++r.liveTriangles_;
  }

  for (std::uint32_t& slot : newSlots) {
    if (r.useCounts_[slot] == 0) {  // added but unused: give the slot back
      r.freeVertices_.push_back(slot);
      slot = kBadSlot;
      continue;
    }
    ++r.liveVertices_;
    if (!boundsDirty) r.bounds_.add(r.vertices_[slot]);
  }
  if (boundsDirty) r.recomputeBounds();

  if (placement) {
    placement->vertexSlots = std::move(newSlots);
    placement->triangleSlots = std::move(triangleSlots);
  }
  return r;
}

}  // namespace reamsim
