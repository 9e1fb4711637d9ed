#pragma once
// Small mesh edits the suites share.
#include <cstdint>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::test {

// `a` and `b` in one mesh, each keeping its own vertices (nothing shared until merged by position).
inline TriangleMesh merged(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh out = a;
  const auto base = std::uint32_t(out.vertices.size());
  out.vertices.insert(out.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Triangle t : b.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return out;
}

}  // namespace reamsim::test
