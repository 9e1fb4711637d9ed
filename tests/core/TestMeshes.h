#pragma once
// Mesh builders and comparisons shared by the core tests.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::test {

// n x n quads on z = 0, spacing 1 mm, row-major order, 2 triangles per quad.
inline TriangleMesh grid(std::uint32_t n) {
  TriangleMesh m;
  for (std::uint32_t j = 0; j <= n; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) m.vertices.push_back({double(i), double(j), 0});
  auto v = [n](std::uint32_t i, std::uint32_t j) { return j * (n + 1) + i; };
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  return m;
}

// Closed, outward-oriented axis-aligned box [0,sx]x[0,sy]x[0,sz].
inline TriangleMesh box(double sx, double sy, double sz) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {sx, 0, 0}, {sx, sy, 0}, {0, sy, 0}, {0, 0, sz}, {sx, 0, sz}, {sx, sy, sz}, {0, sy, sz}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                 {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return m;
}

// A triangle as its three corner coordinates, rotated to a canonical start (orientation kept).
using CoordTriangle = std::array<std::array<double, 3>, 3>;

inline std::vector<CoordTriangle> coordinateTriangles(const TriangleMesh& m) {
  std::vector<CoordTriangle> out;
  for (const Triangle& t : m.triangles) {
    CoordTriangle c;
    for (int k = 0; k < 3; ++k) c[k] = {m.vertices[t[k]].x, m.vertices[t[k]].y, m.vertices[t[k]].z};
    out.push_back(std::min({c, CoordTriangle{c[1], c[2], c[0]}, CoordTriangle{c[2], c[0], c[1]}}));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Same surface up to vertex/triangle order: equal multisets of coordinate triangles.
inline bool sameSurface(const TriangleMesh& a, const TriangleMesh& b) {
  return coordinateTriangles(a) == coordinateTriangles(b);
}

}  // namespace reamsim::test
