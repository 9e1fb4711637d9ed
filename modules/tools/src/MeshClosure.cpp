#include "reamsim/tools/MeshClosure.h"

#include <cstdint>
#include <unordered_map>

namespace reamsim {

std::string ClosureReport::describe() const {
  std::string s;
  auto add = [&s](std::size_t n, const char* what) {
    if (n == 0) return;
    if (!s.empty()) s += ", ";
    s += std::to_string(n) + " " + what + (n == 1 ? "" : "s");
  };
  add(boundaryEdges, "boundary edge");
  add(nonManifoldEdges, "non-manifold edge");
  add(misorientedEdges, "inconsistently oriented edge");
  add(degenerateTriangles, "degenerate triangle");
  return s.empty() ? "closed and consistently oriented" : s;
}

ClosureReport checkClosure(const TriangleMesh& mesh) {
  // Per undirected edge: how often it is walked low->high and high->low.
  struct Use {
    std::uint32_t forward = 0, backward = 0;
  };
  std::unordered_map<std::uint64_t, Use> edges;
  edges.reserve(mesh.triangles.size() * 2);
  ClosureReport r;
  for (const Triangle& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.degenerateTriangles;
      continue;
    }
    const Vec3& a = mesh.vertices[t[0]];
    if (squaredNorm(cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a)) == 0) ++r.degenerateTriangles;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t p = t[i], q = t[(i + 1) % 3];
      const bool fwd = p < q;
      const std::uint64_t key = (static_cast<std::uint64_t>(fwd ? p : q) << 32) | (fwd ? q : p);
      Use& u = edges[key];
      (fwd ? u.forward : u.backward) += 1;
    }
  }
  for (const auto& [key, u] : edges) {
    const std::uint32_t total = u.forward + u.backward;
    if (total == 1)
      ++r.boundaryEdges;
    else if (total > 2)
      ++r.nonManifoldEdges;
    else if (u.forward != 1)
      ++r.misorientedEdges;
  }
  return r;
}

}  // namespace reamsim
