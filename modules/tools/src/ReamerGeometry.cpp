#include "reamsim/tools/ReamerGeometry.h"

#include <cmath>
#include <cstdint>

namespace reamsim {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Ring k (1..rings) of the face, at polar angle k/rings * alpha on the sphere (equal arc steps keep the
// facets well shaped) or at radius k/rings * D/2 on a flat disc.
struct Ring {
  double radius, z;
};
Ring faceRing(const ReamerSpec& spec, int k) {
  const double rimRadius = spec.diameterMm / 2;
  if (spec.isFlat()) return {rimRadius * k / spec.rings, 0};
  if (k == spec.rings) return {rimRadius, -capHeight(spec)};  // exact rim, so the body cylinder lines up with it
  const double alpha = std::asin(std::min(1.0, rimRadius / spec.sphereRadiusMm));
  const double theta = alpha * k / spec.rings, R = spec.sphereRadiusMm;
  return {R * std::sin(theta), -R * (1 - std::cos(theta))};
}
// Vertices on ring k: `segments` on the rim, and on a spherical cap fewer inwards in proportion to the
// ring's radius (at least six), so that the facets keep about the rim's size and shape up to the apex. With
// as many on every ring, the faces near the apex were needles (3.75° at 96 segments): a third of the cap's
// faces, which the cutting engine imprints on the bone with every cut. A flat disc keeps `segments` on every
// ring: its faces lie in the plane of the floor it cut before, and fewer vertices inwards made a disc moved
// sideways at one depth split that floor into many more faces.
int ringSegments(const ReamerSpec& spec, int k) {
  const int n = spec.segments;
  if (k >= spec.rings || spec.isFlat()) return n;
  const int proportional = static_cast<int>(std::lround(n * faceRing(spec, k).radius / (spec.diameterMm / 2)));
  return std::min(n, std::max(std::min(n, 6), proportional));
}

void appendFaceVertices(const ReamerSpec& spec, std::vector<Vec3>& out) {
  out.push_back({0, 0, 0});  // apex
  for (int k = 1; k <= spec.rings; ++k) {
    const Ring r = faceRing(spec, k);
    const int n = ringSegments(spec, k);
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * kPi * j / n;
      out.push_back({r.radius * std::cos(phi), r.radius * std::sin(phi), r.z});
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
// Band between ring a (na vertices, nearer the apex) and ring b (nb vertices), both starting at phi = 0,
// each triangle advancing one ring by one vertex; oriented as appendBand's. The triangle is the one whose
// plane has the other candidate vertex behind it (gift wrapping: the band is the convex hull of the two
// rings, so the solid stays convex and is swept by hulls); coplanar rings are zipped by angle.
void appendZipBand(std::vector<Triangle>& tris, const std::vector<Vec3>& v, Index a, int na, Index b, int nb) {
  int i = 0, j = 0;
  while (i < na || j < nb) {
    bool advanceB = i == na;
    if (i < na && j < nb) {
      const Vec3 &pa = v[a + i % na], &pb = v[b + j % nb], &paNext = v[a + (i + 1) % na], &pbNext = v[b + (j + 1) % nb];
      // < 0: a's next vertex is behind the plane of (pa, pb, pbNext)
      const double behind = dot(cross(pb - pa, pbNext - pa), paNext - pa);
      const double scale = norm(pb - pa) * norm(pbNext - pa) * norm(paNext - pa);
      advanceB = std::abs(behind) > 1e-12 * scale ? behind < 0
                                                  : std::int64_t(j + 1) * na <= std::int64_t(i + 1) * nb;
    }
    const Index ai = a + static_cast<Index>(i % na), bj = b + static_cast<Index>(j % nb);
    if (advanceB) {
      tris.push_back({ai, bj, b + static_cast<Index>((j + 1) % nb)});
      ++j;
    } else {
      tris.push_back({ai, bj, a + static_cast<Index>((i + 1) % na)});
      ++i;
    }
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
  // Ring k = 1..rings: its vertex count and first vertex (the apex is vertex 0).
  std::vector<int> count(static_cast<std::size_t>(rings) + 1, 0);
  std::vector<Index> ringStart(static_cast<std::size_t>(rings) + 2, 1);
  for (int k = 1; k <= rings; ++k) {
    count[k] = ringSegments(spec, k);
    ringStart[k + 1] = ringStart[k] + static_cast<Index>(count[k]);
  }

  // Face: apex fan, then bands outwards to the rim.
  appendFan(m.triangles, 0, ringStart[1], count[1], true);
  for (int k = 1; k < rings; ++k)
    appendZipBand(m.triangles, m.vertices, ringStart[k], count[k], ringStart[k + 1], count[k + 1]);

  const Index rim = ringStart[rings];
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
