#pragma once
#include "TestMeshOps.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim::test {

inline TriangleMesh unitBox(double size = 10, int divisions = 2) {
  return buildBox(Bounds{{0, 0, 0}, {size, size, size}}, divisions);
}

// The same triangles, each with its own three vertices (an STL-like soup).
inline TriangleMesh asSoup(const TriangleMesh& m) {
  TriangleMesh out;
  for (const Triangle& t : m.triangles) {
    const auto base = std::uint32_t(out.vertices.size());
    for (std::uint32_t v : t) out.vertices.push_back(m.vertices[v]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

inline TriangleMesh translated(TriangleMesh m, const Vec3& d) {
  for (Vec3& p : m.vertices) p += d;
  return m;
}

}  // namespace reamsim::test
