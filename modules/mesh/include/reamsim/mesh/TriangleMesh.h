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

}  // namespace reamsim
