#pragma once
// Independent (test-side) checks of solid meshes, so the tests do not trust the library's own checker.
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::test {

// Every undirected edge is used by exactly two triangles, in opposite directions; no degenerate faces.
inline ::testing::AssertionResult isClosedOriented(const TriangleMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const Triangle& t = m.triangles[i];
    for (auto idx : t)
      if (idx >= m.vertices.size()) return ::testing::AssertionFailure() << "index out of range in triangle " << i;
    const Vec3& a = m.vertices[t[0]];
    const double area2 = norm(cross(m.vertices[t[1]] - a, m.vertices[t[2]] - a));
    if (!(area2 > 1e-12)) return ::testing::AssertionFailure() << "degenerate triangle " << i;
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1)
      return ::testing::AssertionFailure() << "directed edge " << edge.first << "->" << edge.second << " used "
                                           << count << " times (misoriented or non-manifold)";
    const auto rev = directed.find({edge.second, edge.first});
    if (rev == directed.end() || rev->second != 1)
      return ::testing::AssertionFailure() << "edge " << edge.first << "-" << edge.second << " is a boundary edge";
  }
  return ::testing::AssertionSuccess();
}

}  // namespace reamsim::test
