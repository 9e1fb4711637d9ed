#include "reamsim/mesh/TriangleMesh.h"

#include <cstring>
#include <limits>
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
  struct Key {
    double x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      const auto bits = [](double d) {
        std::uint64_t u;
        d += 0.0;  // -0 -> +0
        std::memcpy(&u, &d, sizeof u);
        return u;
      };
      return std::size_t(bits(k.x) * 0x9E3779B97F4A7C15ull ^ bits(k.y) * 0xC2B2AE3D27D4EB4Full ^
                         bits(k.z) * 0x165667B19E3779F9ull);
    }
  };
  std::unordered_map<Key, std::uint32_t, Hash> first;
  first.reserve(mesh.vertices.size());
  std::vector<std::uint32_t> out(mesh.vertices.size());
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    out[i] = first.emplace(Key{p.x, p.y, p.z}, i).first->second;
  }
  return out;
}
}  // namespace

std::size_t countCoincidentVertices(const TriangleMesh& mesh) {
  const std::vector<std::uint32_t> first = firstAtPosition(mesh);
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < first.size(); ++i) n += first[i] != i;
  return n;
}

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
  if (merged) {
    std::size_t n = 0;
    for (std::uint32_t i = 0; i < first.size(); ++i) n += first[i] != i;
    *merged = n;
  }
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

}  // namespace reamsim
