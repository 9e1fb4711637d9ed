#pragma once
// One immutable state of the bone surface, cheap to keep many of.
//
// Storage is slot based: vertices and triangles live in PersistentArrays, so a state derived by a
// local edit shares every untouched chunk with its parent. A removed triangle leaves a tombstone
// (all indices kBadSlot) and its slot goes on a free list; a vertex is live while at least one live
// triangle uses it (per-vertex use counts), and its slot is freed when the count drops to zero. New
// elements reuse freed slots first, which keeps a cut's edits inside the chunks it already touched.
//
// Slot numbers are stable across applyDelta/commitByDiff for everything that did not change, and are
// what MeshDelta refers to. Volume and bounds are maintained incrementally.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "reamsim/core/MeshDelta.h"
#include "reamsim/core/PersistentArray.h"
#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

// Triangle slots that differ between two states (a slot whose triangle changed is in both lists).
struct SlotChanges {
  std::vector<std::uint32_t> removed;  // live in the old state, dead or different in the new one
  std::vector<std::uint32_t> added;    // live in the new state, dead or different in the old one
};

class BoneState {
 public:
  static constexpr std::uint32_t kBadSlot = std::numeric_limits<std::uint32_t>::max();
  // 256 elements per chunk (6 KiB of vertices, 3 KiB of triangles): small enough that a 500-triangle
  // cut copies a few tens of KiB, large enough that chunk tables stay short.
  static constexpr std::size_t kChunkSize = 256;

  enum class Ordering {
    Spatial,   // sort vertices and triangles along a Morton curve: local cuts touch few chunks
    Preserve,  // slot i = input index i (unused input vertices become free slots)
  };

  BoneState() = default;  // empty surface
  // Throws std::invalid_argument for an out-of-range index, a non-finite coordinate or > 2^31 vertices.
  // `volumeOrigin`: the point the volume's tetrahedra are taken from (default: the mesh's bounds' centre). The
  // volume of an open surface depends on it; a state read back from a history journal takes the written one's.
  static BoneState fromMesh(const TriangleMesh& mesh, Ordering ordering = Ordering::Spatial,
                            const std::optional<Vec3>& volumeOrigin = std::nullopt);
  // Compact mesh of the live elements, vertices and triangles in slot order.
  TriangleMesh toMesh() const;

  // Returns the edited state; *this is unchanged. Throws std::invalid_argument for an invalid delta
  // (see MeshDelta.h), in which case nothing is returned.
  BoneState applyDelta(const MeshDelta& delta, DeltaPlacement* placement = nullptr) const;
  // For engines that return a whole new mesh: vertices are matched to prev's live vertices by exact
  // coordinates and triangles by vertex-slot triples (rotation-invariant, orientation-sensitive);
  // matched triangles keep their slots, so unchanged regions keep sharing storage with prev. The
  // result's toMesh() equals `next` up to element order (coincident vertices stay distinct).
  static BoneState commitByDiff(const BoneState& prev, const TriangleMesh& next);
  // The triangle slots that changed from `prev` to `next`. States derived from one another (applyDelta,
  // commitByDiff) share their unchanged chunks, which are skipped by identity: O(slots / kChunkSize +
  // changed chunks × kChunkSize), microseconds for a cut of a 400k bone. Unrelated states are compared
  // slot by slot. Sound because vertices never move: a vertex slot takes new coordinates only after it
  // was freed, when no live triangle uses it, so a triangle in a shared chunk keeps its corners. One edit can
  // free a vertex slot, give it to a new vertex and put a triangle with the same corner slots back in the slot
  // it left: in the chunks that differ, a triangle counts as unchanged only if its corners' coordinates do too.
  static SlotChanges changedTriangleSlots(const BoneState& prev, const BoneState& next);

  std::size_t liveTriangleCount() const { return liveTriangles_; }
  std::size_t liveVertexCount() const { return liveVertices_; }
  std::size_t triangleSlotCount() const { return triangles_.size(); }
  std::size_t vertexSlotCount() const { return vertices_.size(); }
  bool empty() const { return liveTriangles_ == 0; }

  bool isTriangleLive(std::uint32_t slot) const { return slot < triangles_.size() && triangles_[slot][0] != kBadSlot; }
  bool isVertexLive(std::uint32_t slot) const { return slot < vertices_.size() && useCounts_[slot] > 0; }
  const Triangle& triangle(std::uint32_t slot) const { return triangles_[slot]; }  // tombstone if dead
  const Vec3& vertex(std::uint32_t slot) const { return vertices_[slot]; }
  std::uint32_t vertexUseCount(std::uint32_t slot) const { return useCounts_[slot]; }

  // Calls f(slot, triangle) for each live triangle in slot order.
  template <class F>
  void forEachLiveTriangle(F&& f) const {
    std::uint32_t slot = 0;
    triangles_.forEach([&](const Triangle& t) {
      if (t[0] != kBadSlot) f(slot, t);
      ++slot;
    });
  }

  double volume() const { return volume6_ / 6.0; }  // signed, as signedVolume(toMesh())
  const Vec3& volumeOrigin() const { return volumeOrigin_; }
  const Bounds& bounds() const { return bounds_; }    // of the live vertices

  // f(identity, bytes) for each heap block this state references (see PersistentArray::visitStorage).
  template <class F>
  void visitStorage(F&& f) const {
    vertices_.visitStorage(f);
    useCounts_.visitStorage(f);
    triangles_.visitStorage(f);
    freeVertices_.visitStorage(f);
    freeTriangles_.visitStorage(f);
  }
  std::size_t storageBytes() const;  // this state alone, as if nothing were shared

 private:
  template <class T>
  using Array = PersistentArray<T, kChunkSize>;

  double volumeTerm(const Triangle& t) const;  // 6 x signed tetra volume against volumeOrigin_
  void recomputeBounds();
  std::uint32_t allocateVertex(const Vec3& p);
  std::uint32_t allocateTriangle(const Triangle& t);
  void freeVertex(std::uint32_t slot, bool& boundsDirty);

  Array<Vec3> vertices_;
  Array<std::uint32_t> useCounts_;  // live triangles using each vertex slot; 0 = free
  Array<Triangle> triangles_;
  Array<std::uint32_t> freeVertices_;   // stack of free vertex slots
  Array<std::uint32_t> freeTriangles_;  // stack of free triangle slots
  std::size_t liveVertices_ = 0;
  std::size_t liveTriangles_ = 0;
  Vec3 volumeOrigin_;  // fixed at fromMesh so incremental updates add up like the full sum
  double volume6_ = 0;
  Bounds bounds_;
};

// Memory held by a set of states, each storage block counted once.
struct StorageStats {
  std::size_t uniqueBytes = 0;   // distinct blocks: the memory actually held
  std::size_t sharedBytes = 0;   // distinct blocks referenced by two or more states
  std::size_t logicalBytes = 0;  // sum of each state's own size: what independent copies would take
};
StorageStats measureStorage(const std::vector<const BoneState*>& states);

}  // namespace reamsim
