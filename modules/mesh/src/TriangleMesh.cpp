#include "reamsim/mesh/TriangleMesh.h"

#include <algorithm>
#include <limits>
#include <map>
#include <unordered_map>

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

namespace {
// Index of the first vertex at each position (exact equality; -0 and +0 are the same position).
std::vector<std::uint32_t> firstAtPosition(const TriangleMesh& mesh) {
  std::unordered_map<Vec3, std::uint32_t, Vec3PositionHash> first;
  first.reserve(mesh.vertices.size());
  std::vector<std::uint32_t> out(mesh.vertices.size());
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) out[i] = first.emplace(mesh.vertices[i], i).first->second;
  return out;
}
// Vertices that are not the first at their position.
std::size_t countNotFirst(const std::vector<std::uint32_t>& first) {
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < first.size(); ++i) n += first[i] != i;
  return n;
}
}  // namespace

std::size_t countCoincidentVertices(const TriangleMesh& mesh) { return countNotFirst(firstAtPosition(mesh)); }

TriangleMesh mergeCoincidentVertices(const TriangleMesh& mesh, std::size_t* merged) {
  const std::vector<std::uint32_t> first = firstAtPosition(mesh);
  TriangleMesh out;
  out.vertices = mesh.vertices;
  out.triangles.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    Triangle u = t;
    for (std::uint32_t& v : u)
      if (v < first.size()) v = first[v];
    out.triangles.push_back(u);
  }
  removeUnusedVertices(out);
  if (merged) *merged = countNotFirst(first);
  return out;
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

TriangleMesh subdivideMidpoints(const TriangleMesh& in) {
  TriangleMesh out;
  out.vertices = in.vertices;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, added] = mid.try_emplace(std::minmax(a, b), std::uint32_t(out.vertices.size()));
    if (added) out.vertices.push_back((in.vertices[a] + in.vertices[b]) * 0.5);
    return it->second;
  };
  for (const Triangle& t : in.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

}  // namespace reamsim
