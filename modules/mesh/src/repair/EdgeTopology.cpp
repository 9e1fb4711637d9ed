#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "reamsim/mesh/Validation.h"

namespace reamsim {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

struct EdgeUse {
  std::uint32_t count = 0;
  std::uint32_t forward = 0;  // traversals from the smaller to the larger index
};

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

bool isDegenerate(const TriangleMesh& mesh, const Triangle& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  const Vec3& a = mesh.vertices[t[0]];
  const Vec3 n = cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a);
  return n == Vec3{0, 0, 0};
}

}  // namespace

EdgeTopology analyzeEdges(const TriangleMesh& mesh) {
  EdgeTopology topo;
  std::unordered_map<std::uint64_t, EdgeUse> uses;
  uses.reserve(mesh.triangles.size() * 2);
  std::vector<std::uint32_t> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<bool> used(mesh.vertices.size(), false);

  for (const Triangle& t : mesh.triangles) {
    if (isDegenerate(mesh, t)) ++topo.degenerateFaces;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      used[a] = true;
      if (a == b) continue;
      EdgeUse& use = uses[edgeKey(a, b)];
      ++use.count;
      if (a < b) ++use.forward;
      const std::uint32_t ra = findRoot(parent, a), rb = findRoot(parent, b);
      if (ra != rb) parent[ra] = rb;
    }
  }
  topo.edges = uses.size();
  for (const auto& [key, use] : uses) {
    if (use.count == 1) ++topo.boundaryEdges;
    else if (use.count > 2) ++topo.nonManifoldEdges;
    else if (use.forward != 1) ++topo.inconsistentEdges;
  }
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!used[v]) ++topo.isolatedVertices;
    else if (findRoot(parent, v) == v) ++topo.connectedComponents;
  }
  return topo;
}

}  // namespace reamsim
