#pragma once
// The validation report: what a mesh is, topologically and geometrically, before anyone cuts it.
#include <cstddef>
#include <optional>
#include <string>

#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct EdgeTopology {
  std::size_t edges = 0;             // undirected edges
  std::size_t boundaryEdges = 0;     // used by exactly one triangle
  std::size_t nonManifoldEdges = 0;  // used by three or more triangles
  std::size_t inconsistentEdges = 0; // two triangles traverse the edge in the same direction
  std::size_t degenerateFaces = 0;   // repeated vertex index or zero area
  std::size_t connectedComponents = 0;
  std::size_t isolatedVertices = 0;
  bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
  bool consistentlyOriented() const { return inconsistentEdges == 0; }
};

EdgeTopology analyzeEdges(const TriangleMesh& mesh);

struct ValidationOptions {
  bool checkSelfIntersections = true;
  std::size_t maxSelfIntersectionPairs = 1000000;  // stop counting beyond this
  // Reported while self-intersections are counted (seconds at millions of triangles); throws
  // RepairCancelled when asked to stop.
  StageProgress progress;
};

struct ValidationReport {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  EdgeTopology topology;
  bool closed = false;
  bool consistentlyOriented = false;
  bool outwardOriented = false;  // closed, consistent and positive volume
  std::optional<std::size_t> selfIntersectingPairs;  // empty when not checked
  std::optional<double> volumeMm3;                   // only when closed and consistently oriented
  // Vertices at the position of an earlier vertex (see countCoincidentVertices). When there are any, the
  // mesh is also analysed with them merged: a seam that only fails to share indices is told apart from a
  // real border or a real self-intersection.
  std::size_t coincidentVertices = 0;
  struct AfterMerging {
    std::size_t boundaryEdges = 0;
    std::size_t nonManifoldEdges = 0;
    std::optional<std::size_t> selfIntersectingPairs;  // empty when not checked
  };
  std::optional<AfterMerging> afterMergingCoincident;
  double areaMm2 = 0;
  Bounds bounds;

  bool isCleanSolid() const {
    return closed && consistentlyOriented && outwardOriented && selfIntersectingPairs.value_or(1) == 0 &&
           topology.degenerateFaces == 0;
  }
};

ValidationReport validateMesh(const TriangleMesh& mesh, const ValidationOptions& options = {});

// Number of pairs of triangles that intersect other than along a shared edge or vertex (CGAL, exact
// predicates). Non-manifold input is first split into a valid polygon mesh, as CGAL requires. Checks
// `progress` between slabs of about 200,000 faces.
std::size_t countSelfIntersections(const TriangleMesh& mesh, std::size_t maxPairs = 1000000,
                                   const StageProgress& progress = {});

namespace detail {
// countSelfIntersections with the slab size given (at most 64 slabs): the count does not depend on it.
std::size_t countSelfIntersectionsInSlabs(const TriangleMesh& mesh, std::size_t maxPairs, const StageProgress& progress,
                                          std::size_t facesPerSlab);
}  // namespace detail

std::string toText(const ValidationReport& report);
std::string toJson(const ValidationReport& report, int indent = 2);

}  // namespace reamsim
