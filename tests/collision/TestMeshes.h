#pragma once
// Small closed meshes built by hand for the collision tests.
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::test {

// Closed, outward-oriented axis-aligned box: 8 vertices (index bits x=1, y=2, z=4), 12 triangles.
inline TriangleMesh makeBox(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  m.triangles = {{0, 2, 3}, {0, 3, 1},   // -z
                 {4, 5, 7}, {4, 7, 6},   // +z
                 {0, 1, 5}, {0, 5, 4},   // -y
                 {2, 6, 7}, {2, 7, 3},   // +y
                 {0, 4, 6}, {0, 6, 2},   // -x
                 {1, 3, 7}, {1, 7, 5}};  // +x
  return m;
}

}  // namespace reamsim::test
