#include "reamsim/mesh/TriangleMesh.h"

#include <limits>

namespace reamsim {

Bounds computeBounds(const TriangleMesh& mesh) {
  Bounds b;
  for (const Vec3& p : mesh.vertices) b.add(p);
  return b;
}

double signedVolume(const TriangleMesh& mesh) {
  // Sum of signed tetrahedra against a reference point near the mesh, which keeps rounding small.
  const Vec3 o = computeBounds(mesh).center();
  double sum = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o, c = mesh.vertices[t[2]] - o;
    sum += dot(a, cross(b, c));
  }
  return sum / 6.0;
}

double surfaceArea(const TriangleMesh& mesh) {
  double sum = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    sum += 0.5 * norm(cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a));
  }
  return sum;
}

void scaleInPlace(TriangleMesh& mesh, double factor) {
  for (Vec3& p : mesh.vertices) p *= factor;
}

std::size_t removeUnusedVertices(TriangleMesh& mesh) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(mesh.vertices.size(), kUnused);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) remap[v] = 0;
  std::vector<Vec3> kept;
  kept.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < remap.size(); ++i) {
    if (remap[i] == kUnused) continue;
    remap[i] = static_cast<std::uint32_t>(kept.size());
    kept.push_back(mesh.vertices[i]);
  }
  const std::size_t removed = mesh.vertices.size() - kept.size();
  for (Triangle& t : mesh.triangles)
    for (std::uint32_t& v : t) v = remap[v];
  mesh.vertices = std::move(kept);
  return removed;
}

}  // namespace reamsim
