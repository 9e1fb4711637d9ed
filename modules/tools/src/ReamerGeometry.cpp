#include "reamsim/tools/ReamerGeometry.h"

#include <cmath>
#include <cstdint>

namespace reamsim {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Ring k (1..rings) of the face, at polar angle k/rings * alpha on the sphere (equal arc steps keep the
// facets well shaped) or at radius k/rings * D/2 on a flat disc.
void appendFaceVertices(const ReamerSpec& spec, std::vector<Vec3>& out) {
  const int n = spec.segments, rings = spec.rings;
  const double rimRadius = spec.diameterMm / 2;
  out.reserve(out.size() + 1 + static_cast<std::size_t>(n) * rings);
  out.push_back({0, 0, 0});  // apex
  const double alpha = spec.isFlat() ? 0.0 : std::asin(std::min(1.0, rimRadius / spec.sphereRadiusMm));
  for (int k = 1; k <= rings; ++k) {
    double radius, z;
    if (spec.isFlat()) {
      radius = rimRadius * k / rings;
      z = 0;
    } else if (k == rings) {
      radius = rimRadius;  // exact rim, so the body cylinder lines up with it
      z = -capHeight(spec);
    } else {
      const double theta = alpha * k / rings, R = spec.sphereRadiusMm;
      radius = R * std::sin(theta);
      z = -R * (1 - std::cos(theta));
    }
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * kPi * j / n;
      out.push_back({radius * std::cos(phi), radius * std::sin(phi), z});
    }
  }
}

void appendRing(std::vector<Vec3>& out, double radius, double z, int n) {
  for (int j = 0; j < n; ++j) {
    const double phi = 2 * kPi * j / n;
    out.push_back({radius * std::cos(phi), radius * std::sin(phi), z});
  }
}

using Index = std::uint32_t;
// Side band between ring a (nearer +Z) and ring b (further along -Z), both CCW seen from +Z; faces point
// away from the axis for a cylinder and away from the sphere centre for a cap band.
void appendBand(std::vector<Triangle>& tris, Index a, Index b, int n) {
  for (int j = 0; j < n; ++j) {
    const Index jn = static_cast<Index>((j + 1) % n), jj = static_cast<Index>(j);
    tris.push_back({a + jj, b + jj, b + jn});
    tris.push_back({a + jj, b + jn, a + jn});
  }
}
// Fan from `centre` to ring `r`; `towardPlusZ` selects the normal direction.
void appendFan(std::vector<Triangle>& tris, Index centre, Index r, int n, bool towardPlusZ) {
  for (int j = 0; j < n; ++j) {
    const Index jn = static_cast<Index>((j + 1) % n), jj = static_cast<Index>(j);
    if (towardPlusZ)
      tris.push_back({centre, r + jj, r + jn});
    else
      tris.push_back({centre, r + jn, r + jj});
  }
}
}  // namespace

std::vector<Vec3> cuttingFaceVertices(const ReamerSpec& spec) {
  validateReamerSpec(spec);
  std::vector<Vec3> v;
  appendFaceVertices(spec, v);
  return v;
}

TriangleMesh buildCuttingSolid(const ReamerSpec& spec) {
  validateReamerSpec(spec);
  const int n = spec.segments, rings = spec.rings;
  TriangleMesh m;
  appendFaceVertices(spec, m.vertices);
  auto ringStart = [n](int k) { return static_cast<Index>(1 + (k - 1) * n); };  // ring k = 1..rings

  // Face: apex fan, then bands outwards to the rim.
  appendFan(m.triangles, 0, ringStart(1), n, true);
  for (int k = 1; k < rings; ++k) appendBand(m.triangles, ringStart(k), ringStart(k + 1), n);

  const Index rim = ringStart(rings);
  const double rimZ = m.vertices[rim].z;
  Index back = rim;  // ring closed by the back disc
  if (spec.bodyLengthMm > 0) {
    back = static_cast<Index>(m.vertices.size());
    appendRing(m.vertices, spec.diameterMm / 2, rimZ - spec.bodyLengthMm, n);
    appendBand(m.triangles, rim, back, n);
  }
  const Index centre = static_cast<Index>(m.vertices.size());
  m.vertices.push_back({0, 0, m.vertices[back].z});
  appendFan(m.triangles, centre, back, n, false);
  return m;
}

TriangleMesh buildClosedCylinder(double radius, double z0, double z1, int segments) {
  TriangleMesh m;
  if (!(radius > 0) || !(z1 > z0) || segments < 3) return m;
  const int n = segments;
  m.vertices.push_back({0, 0, z1});
  appendRing(m.vertices, radius, z1, n);
  appendRing(m.vertices, radius, z0, n);
  m.vertices.push_back({0, 0, z0});
  const Index top = 1, bottom = static_cast<Index>(1 + n), centre = static_cast<Index>(1 + 2 * n);
  appendFan(m.triangles, 0, top, n, true);
  appendBand(m.triangles, top, bottom, n);
  appendFan(m.triangles, centre, bottom, n, false);
  return m;
}

}  // namespace reamsim
