#pragma once
// Topology check for solids: a mesh bounds a volume when every undirected edge is used by exactly two
// triangles that traverse it in opposite directions (closed, 2-manifold along edges, consistently oriented).
#include <cstddef>
#include <string>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct ClosureReport {
  std::size_t boundaryEdges = 0;       // used by one triangle
  std::size_t nonManifoldEdges = 0;    // used by more than two triangles
  std::size_t misorientedEdges = 0;    // used twice in the same direction
  std::size_t degenerateTriangles = 0; // repeated vertex index or zero area
  bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0; }
  std::string describe() const;  // e.g. "3 boundary edges, 1 misoriented edge"
};

ClosureReport checkClosure(const TriangleMesh& mesh);

}  // namespace reamsim
