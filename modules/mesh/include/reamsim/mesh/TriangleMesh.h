#pragma once
// The plain, indexed triangle mesh every module exchanges. Geometry in millimetres once imported.
#include <array>
#include <cstdint>
#include <vector>

#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

using Triangle = std::array<std::uint32_t, 3>;

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;

  std::size_t vertexCount() const { return vertices.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }
};

Bounds computeBounds(const TriangleMesh& mesh);
// Signed volume by the divergence theorem (positive for a closed, outward-oriented mesh).
double signedVolume(const TriangleMesh& mesh);
double surfaceArea(const TriangleMesh& mesh);
void scaleInPlace(TriangleMesh& mesh, double factor);
// Removes vertices no triangle uses and renumbers; returns how many were removed.
std::size_t removeUnusedVertices(TriangleMesh& mesh);
// Vertices at exactly the position of an earlier vertex: seams that meet only geometrically (files written
// strip by strip or patch by patch). Triangles on either side of such a seam share no index, so edge
// topology sees a border there and self-intersection tests see triangles touching at an unshared point.
std::size_t countCoincidentVertices(const TriangleMesh& mesh);
// The same mesh with coincident vertices made one (the first index of each position kept; unused vertices
// removed). Returns how many vertices were merged away through `merged` when given.
TriangleMesh mergeCoincidentVertices(const TriangleMesh& mesh, std::size_t* merged = nullptr);
// Each triangle split in four at its edges' midpoints (shared by the triangles of an edge): the same surface,
// four times the triangles, orientation kept.
TriangleMesh subdivideMidpoints(const TriangleMesh& mesh);

}  // namespace reamsim
