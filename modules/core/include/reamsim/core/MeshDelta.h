#pragma once
// A local edit of a BoneState, expressed in its slots: cost of applying it is O(delta + chunks touched).
//
// Encoding of vertex references in addedTriangles:
//  - a value without the high bit is an existing vertex slot of the state the delta is applied to
//    (it must be live there, i.e. used by at least one triangle);
//  - MeshDelta::newVertex(i) (i | 0x80000000) refers to addedVertices[i].
// Triangle slots in removedTriangles must be live and distinct. Orientation is kept as given.
#include <cstdint>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct MeshDelta {
  static constexpr std::uint32_t kNewVertexBit = 0x80000000u;
  static constexpr std::uint32_t newVertex(std::uint32_t i) { return i | kNewVertexBit; }
  static constexpr bool isNewVertex(std::uint32_t ref) { return (ref & kNewVertexBit) != 0; }
  static constexpr std::uint32_t newVertexIndex(std::uint32_t ref) { return ref & ~kNewVertexBit; }

  std::vector<std::uint32_t> removedTriangles;  // triangle slots
  std::vector<Vec3> addedVertices;
  std::vector<Triangle> addedTriangles;         // see the encoding above

  bool empty() const { return removedTriangles.empty() && addedVertices.empty() && addedTriangles.empty(); }
};

// Where applyDelta put things, so an engine can address them in its next delta.
struct DeltaPlacement {
  std::vector<std::uint32_t> vertexSlots;    // per addedVertices entry; UINT32_MAX if no triangle used it
  std::vector<std::uint32_t> triangleSlots;  // per addedTriangles entry
};

}  // namespace reamsim
