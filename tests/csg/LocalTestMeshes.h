#pragma once
// Bones and tools for the local engine's tests: blocks, a UV sphere, reamers at a pose.
#include <cmath>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim::test {

inline TriangleMesh toolAt(const ReamerSpec& spec, const Pose& pose) {
  TriangleMesh m = buildCuttingSolid(spec);
  const RigidTransform t = toTransform(pose);
  for (Vec3& p : m.vertices) p = t.apply(p);
  return m;
}

inline ReamerSpec flatSpec(double diameter, int segments = 64) {
  ReamerSpec s;
  s.name = "flat";
  s.diameterMm = diameter;
  s.bodyLengthMm = 10;
  s.segments = segments;
  s.rings = 4;
  return s;
}

inline ReamerSpec capSpec(double diameter, double radius, int segments = 96, int rings = 12) {
  ReamerSpec s;
  s.name = "cap";
  s.diameterMm = diameter;
  s.sphereRadiusMm = radius;
  s.bodyLengthMm = 12;
  s.segments = segments;
  s.rings = rings;
  return s;
}

// Closed, outward UV sphere about `c` with poles on the Z axis (a vertex at the top pole).
inline TriangleMesh uvSphere(const Vec3& c, double r, int segments, int rings) {
  TriangleMesh m;
  m.vertices.push_back(c + Vec3{0, 0, r});
  for (int i = 1; i < rings; ++i) {
    const double th = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * M_PI * j / segments;
      m.vertices.push_back(c + Vec3{r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  }
  m.vertices.push_back(c - Vec3{0, 0, r});
  const auto ring = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * segments + (j % segments)); };
  const std::uint32_t bottom = std::uint32_t(m.vertices.size() - 1);
  for (int j = 0; j < segments; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.triangles.push_back({bottom, ring(rings - 1, j + 1), ring(rings - 1, j)});
  return m;
}

// A spherical reamer's cutting solid with `segments` vertices on every ring (the presets' tessellation until
// session 16): near the apex its facets are needles (360° / segments at the apex), which the band clean-up
// can improve without touching the intersection curve. At `pose`.
inline TriangleMesh uniformRingCapAt(double diameter, double radius, double body, int segments, int rings,
                                     const Pose& pose) {
  TriangleMesh m;
  const double alpha = std::asin(diameter / 2 / radius), h = radius - std::sqrt(radius * radius - diameter * diameter / 4);
  m.vertices.push_back({0, 0, 0});
  auto addRing = [&](double r, double z) {
    for (int j = 0; j < segments; ++j)
      m.vertices.push_back({r * std::cos(2 * M_PI * j / segments), r * std::sin(2 * M_PI * j / segments), z});
  };
  for (int k = 1; k < rings; ++k)
    addRing(radius * std::sin(alpha * k / rings), -radius * (1 - std::cos(alpha * k / rings)));
  addRing(diameter / 2, -h);
  addRing(diameter / 2, -h - body);
  m.vertices.push_back({0, 0, -h - body});
  const auto at = [&](int ring, int j) { return std::uint32_t(1 + (ring - 1) * segments + j % segments); };
  const std::uint32_t back = std::uint32_t(m.vertices.size() - 1);
  for (int j = 0; j < segments; ++j) m.triangles.push_back({0, at(1, j), at(1, j + 1)});
  for (int k = 1; k <= rings; ++k)  // the face's bands, then the body's (ring rings + 1 is the back ring)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({at(k, j), at(k + 1, j), at(k + 1, j + 1)});
      m.triangles.push_back({at(k, j), at(k + 1, j + 1), at(k, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.triangles.push_back({back, at(rings + 1, j + 1), at(rings + 1, j)});
  const RigidTransform t = toTransform(pose);
  for (Vec3& p : m.vertices) p = t.apply(p);
  return m;
}

inline double sphericalCapVolume(double radius, double height) {
  return M_PI * height * height * (3 * radius - height) / 3;
}

}  // namespace reamsim::test
