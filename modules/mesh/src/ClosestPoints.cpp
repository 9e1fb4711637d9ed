#include "reamsim/mesh/ClosestPoints.h"

#include <algorithm>

namespace reamsim {

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleRegion* region) {
  TriangleRegion dummy;
  TriangleRegion& r = region ? *region : dummy;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) { r = TriangleRegion::VertexA; return a; }
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) { r = TriangleRegion::VertexB; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    r = TriangleRegion::EdgeAB;
    const double v = d1 / (d1 - d3);
    return a + ab * v;
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) { r = TriangleRegion::VertexC; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    r = TriangleRegion::EdgeCA;
    const double w = d2 / (d2 - d6);
    return a + ac * w;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    r = TriangleRegion::EdgeBC;
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return b + (c - b) * w;
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) {
    // Degenerate (zero-area) triangle: closest point over its three edges.
    Vec3 best = a, c1, c2;
    double bestD = squaredNorm(p - a), s, t;
    r = TriangleRegion::VertexA;
    const Vec3 e[3][2] = {{a, b}, {b, c}, {c, a}};
    const TriangleRegion er[3] = {TriangleRegion::EdgeAB, TriangleRegion::EdgeBC, TriangleRegion::EdgeCA};
    for (int i = 0; i < 3; ++i) {
      const double d = closestSegmentSegment(p, p, e[i][0], e[i][1], s, t, c1, c2);
      if (d < bestD) { bestD = d; best = c2; r = er[i]; }
    }
    return best;
  }
  r = TriangleRegion::Face;
  const double v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;
}

double closestSegmentSegment(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, double& s, double& t,
                             Vec3& c1, Vec3& c2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  constexpr double tiny = 1e-300;
  if (a <= tiny && e <= tiny) {
    s = t = 0;
    c1 = p1;
    c2 = p2;
    return squaredNorm(c1 - c2);
  }
  if (a <= tiny) {
    s = 0;
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= tiny) {
      t = 0;
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2);
      const double denom = a * e - b * b;
      s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + d1 * s;
  c2 = p2 + d2 * t;
  return squaredNorm(c1 - c2);
}

}  // namespace reamsim
