#pragma once
// Fast exact self-intersection search for the large, fine meshes that come out of CT isosurfacing, where
// CGAL's general box-intersection search is too slow to run inside the import loop (seconds for 500k faces).
// Broad phase: a uniform grid sized to the triangles, each candidate pair handled in exactly one cell,
// cells processed in parallel. Narrow phase: CGAL's exact predicates (Epick), with the same rules as
// CGAL::Polygon_mesh_processing::self_intersections: faces sharing an edge intersect only if coplanar and
// overlapping; faces sharing a vertex only if an opposite edge meets the other face; other pairs if they
// meet at all. Degenerate (zero-area) faces are not paired; they are counted separately.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::ct {

struct SelfIntersectionResult {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (i < j), sorted; at most maxPairs
  std::vector<std::uint32_t> degenerateFaces;  // zero-area faces (exact test), sorted
  bool truncated = false;  // more pairs exist than were returned
};

// `onlyFaces` (optional, one flag per face): only pairs with at least one flagged face are searched.
SelfIntersectionResult findSelfIntersections(const TriangleMesh& mesh, std::size_t maxPairs = 1000000,
                                             const std::vector<std::uint8_t>* onlyFaces = nullptr);

}  // namespace reamsim::ct
