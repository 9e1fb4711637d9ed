#pragma once
// Meshes, reamers and random poses shared by the collision property tests. Everything is deterministic
// (fixed seeds). Bone meshes are kept moderate (<= ~1.5k triangles) so that the brute-force references can
// answer >= 10,000 queries per type within the test time budget; the 15k-400k bones are left to the bench.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/core/Pose.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim::test {

// Closed, outward icosphere (subdivided icosahedron, vertices projected on the sphere).
inline TriangleMesh icosphere(int subdivisions, double radius, const Vec3& centre) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    TriangleMesh next;
    next.vertices = m.vertices;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      next.vertices.push_back((next.vertices[a] + next.vertices[b]) * 0.5);
      return mid[key] = static_cast<std::uint32_t>(next.vertices.size() - 1);
    };
    for (const Triangle& tr : m.triangles) {
      const std::uint32_t ab = midpoint(tr[0], tr[1]), bc = midpoint(tr[1], tr[2]), ca = midpoint(tr[2], tr[0]);
      next.triangles.push_back({tr[0], ab, ca});
      next.triangles.push_back({tr[1], bc, ab});
      next.triangles.push_back({tr[2], ca, bc});
      next.triangles.push_back({ab, bc, ca});
    }
    m = std::move(next);
  }
  for (Vec3& v : m.vertices) v = centre + normalized(v) * radius;
  return m;
}

// The bundled OpenSim scapula as shipped (1,543 triangles, dirty: open, not consistently oriented), in mm.
inline TriangleMesh bundledScapula() {
  return readMesh(std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp").mesh;
}
// The repaired default bone (14,998 triangles, closed).
inline TriangleMesh defaultScapula() {
  return readMesh(std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_repaired.ply").mesh;
}

// A block with finely divided faces (closed, outward).
inline TriangleMesh block(const Vec3& lo, const Vec3& hi, int divisions) {
  Bounds b;
  b.add(lo);
  b.add(hi);
  return buildBox(b, divisions);
}

// Coarse reamers keep the brute force affordable; the geometry is the real parametric one.
inline ReamerSpec smallSpec(bool flat, int segments = 12, int rings = 3) {
  ReamerSpec s;
  s.name = flat ? "test-flat-20" : "test-20-R16";
  s.diameterMm = 20;
  s.sphereRadiusMm = flat ? std::numeric_limits<double>::infinity() : 16;
  s.bodyLengthMm = 6;
  s.segments = segments;
  s.rings = rings;
  return s;
}

inline Vec3 triangleNormal(const TriangleMesh& m, std::size_t i) {
  const Triangle& t = m.triangles[i];
  return normalized(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]));
}

// v rotated about the unit axis k by angle (Rodrigues).
inline Vec3 rotate(const Vec3& v, const Vec3& k, double angle) {
  return v * std::cos(angle) + cross(k, v) * std::sin(angle) + k * (dot(k, v) * (1 - std::cos(angle)));
}

struct SurfaceSample {
  Vec3 point, normal;
  std::size_t triangle;
};

inline SurfaceSample sampleSurface(const TriangleMesh& m, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
  std::uniform_real_distribution<double> u(0, 1);
  for (;;) {
    const std::size_t i = pick(rng);
    const Vec3 n = triangleNormal(m, i);
    if (norm(n) == 0) continue;
    double a = u(rng), b = u(rng);
    if (a + b > 1) { a = 1 - a; b = 1 - b; }
    const Triangle& t = m.triangles[i];
    const Vec3 p = m.vertices[t[0]] + (m.vertices[t[1]] - m.vertices[t[0]]) * a + (m.vertices[t[2]] - m.vertices[t[0]]) * b;
    return {p, n, i};
  }
}

// A pose whose tip lies `offset` mm off the surface (negative: inside), feeding towards it, tilted by up to
// maxTiltDeg from the surface normal.
inline Pose poseNearSurface(const TriangleMesh& m, std::mt19937_64& rng, double minOffset, double maxOffset,
                            double maxTiltDeg) {
  std::uniform_real_distribution<double> u(0, 1);
  const SurfaceSample s = sampleSurface(m, rng);
  const double pi = 3.14159265358979323846;
  const Vec3 k = rotate(anyPerpendicular(s.normal), s.normal, 2 * pi * u(rng));
  const Vec3 axis = rotate(-s.normal, k, maxTiltDeg * pi / 180 * u(rng));
  const double offset = minOffset + (maxOffset - minOffset) * u(rng);
  Pose p;
  p.axis = normalized(axis);
  p.tip = s.point - p.axis * offset;
  p.rollDeg = 360 * u(rng);
  return p;
}

inline double scaleOf(const TriangleMesh& m) { return computeBounds(m).diagonal(); }

}  // namespace reamsim::test
