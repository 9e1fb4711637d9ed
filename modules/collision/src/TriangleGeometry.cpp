#include "reamsim/collision/TriangleGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reamsim {

namespace {

inline double l1(const Vec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }
inline double maxAbs(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// True when `axis` separates the two (shifted) triangles by more than the touch tolerance.
inline bool separatedAlong(const Vec3& axis, const Vec3 (&a)[3], const Vec3 (&b)[3], double mag) {
  const double pa0 = dot(axis, a[0]), pa1 = dot(axis, a[1]), pa2 = dot(axis, a[2]);
  const double pb0 = dot(axis, b[0]), pb1 = dot(axis, b[1]), pb2 = dot(axis, b[2]);
  const double tol = kTouchEpsilon * l1(axis) * mag;
  const double minA = std::min({pa0, pa1, pa2}), maxA = std::max({pa0, pa1, pa2});
  const double minB = std::min({pb0, pb1, pb2}), maxB = std::max({pb0, pb1, pb2});
  return maxA < minB - tol || maxB < minA - tol;
}

// Segment p->q against triangle abc (Moeller-Trumbore with s in [0, 1]); non-coplanar crossings only.
bool segmentTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& hit) {
  const Vec3 d = q - p, e1 = b - a, e2 = c - a;
  const Vec3 h = cross(d, e2);
  const double det = dot(e1, h);
  if (!(std::abs(det) > 1e-14 * norm(d) * norm(e1) * norm(e2))) return false;
  const double inv = 1.0 / det;
  const Vec3 s = p - a;
  const double u = dot(s, h) * inv;
  constexpr double eps = 1e-9;
  if (u < -eps || u > 1 + eps) return false;
  const Vec3 qv = cross(s, e1);
  const double v = dot(d, qv) * inv;
  if (v < -eps || u + v > 1 + eps) return false;
  const double t = dot(e2, qv) * inv;
  if (t < -eps || t > 1 + eps) return false;
  hit = p + d * std::clamp(t, 0.0, 1.0);
  return true;
}

}  // namespace

bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                        const Vec3& b2) {
  // Work relative to a0 so that the tolerance scales with the configuration, not with the distance to the
  // world origin.
  const Vec3 a[3] = {Vec3{}, a1 - a0, a2 - a0};
  const Vec3 b[3] = {b0 - a0, b1 - a0, b2 - a0};
  const double mag = std::max({maxAbs(a[1]), maxAbs(a[2]), maxAbs(b[0]), maxAbs(b[1]), maxAbs(b[2])}) + 1e-300;
  const Vec3 ea[3] = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
  const Vec3 eb[3] = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
  const Vec3 na = cross(ea[0], a[2] - a[0]);
  const Vec3 nb = cross(eb[0], b[2] - b[0]);
  if (separatedAlong(na, a, b, mag) || separatedAlong(nb, a, b, mag)) return false;
  for (const Vec3& u : ea)
    for (const Vec3& v : eb)
      if (separatedAlong(cross(u, v), a, b, mag)) return false;
  // In-plane edge normals: needed when the triangles are coplanar (harmless otherwise: any axis is sound).
  for (const Vec3& u : ea)
    if (separatedAlong(cross(na, u), a, b, mag)) return false;
  for (const Vec3& v : eb)
    if (separatedAlong(cross(nb, v), a, b, mag)) return false;
  return true;
}

ClosestPair closestTriangleTriangle(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                                    const Vec3& b2) {
  const Vec3 A[3] = {a0, a1, a2}, B[3] = {b0, b1, b2};
  const bool intersecting = trianglesIntersect(a0, a1, a2, b0, b1, b2);
  if (intersecting) {
    Vec3 hit;
    for (int i = 0; i < 3; ++i)
      if (segmentTriangle(A[i], A[(i + 1) % 3], b0, b1, b2, hit)) return {0, hit, hit};
    for (int i = 0; i < 3; ++i)
      if (segmentTriangle(B[i], B[(i + 1) % 3], a0, a1, a2, hit)) return {0, hit, hit};
  }
  ClosestPair best = closestDisjointTriangles(a0, a1, a2, b0, b1, b2);
  // Coplanar overlap or touching within tolerance: the features give the (near-)contact points.
  if (intersecting) best.squaredDistance = 0;
  return best;
}

namespace {
// The foot of a point on a triangle's plane, when it lies inside the triangle (barycentric coordinates from
// the edges' Gram matrix). A sliver (edges all but parallel) is not `usable`: its vertex pairs then go
// through closestPointOnTriangle.
struct InteriorFoot {
  Vec3 t0, e0, e1;
  double d00, d01, d11, denom;
  bool usable;
  InteriorFoot(const Vec3& a, const Vec3& b, const Vec3& c) : t0(a), e0(b - a), e1(c - a) {
    d00 = dot(e0, e0);
    d01 = dot(e0, e1);
    d11 = dot(e1, e1);
    denom = d00 * d11 - d01 * d01;
    usable = denom > 1e-12 * d00 * d11;
  }
  bool find(const Vec3& p, Vec3& foot) const {
    const Vec3 w = p - t0;
    const double d20 = dot(w, e0), d21 = dot(w, e1);
    const double beta = d11 * d20 - d01 * d21, gamma = d00 * d21 - d01 * d20;
    if (!(beta >= 0 && gamma >= 0 && beta + gamma <= denom)) return false;
    foot = t0 + e0 * (beta / denom) + e1 * (gamma / denom);
    return true;
  }
};
}  // namespace

ClosestPair closestDisjointTriangles(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                                     const Vec3& b2) {
  const Vec3 A[3] = {a0, a1, a2}, B[3] = {b0, b1, b2};
  ClosestPair best;
  best.squaredDistance = std::numeric_limits<double>::infinity();
  // Vertex against face only where the vertex's foot lies inside the other triangle: otherwise that
  // triangle's nearest point is on one of its edges, and the edge pairs below, which include the vertex's
  // own two edges, find a pair at least as close. (A full closest-point test per vertex cost ~4x as much.)
  const InteriorFoot onA(a0, a1, a2), onB(b0, b1, b2);
  for (int i = 0; i < 3; ++i) {
    Vec3 q;
    if (onB.usable ? onB.find(A[i], q) : (q = closestPointOnTriangle(A[i], b0, b1, b2), true)) {
      const double d = squaredNorm(A[i] - q);
      if (d < best.squaredDistance) best = {d, A[i], q};
    }
    Vec3 p;
    if (onA.usable ? onA.find(B[i], p) : (p = closestPointOnTriangle(B[i], a0, a1, a2), true)) {
      const double e = squaredNorm(B[i] - p);
      if (e < best.squaredDistance) best = {e, p, B[i]};
    }
  }
  // The nearest pair proves itself: along v = onB - onA the triangles' ranges are apart by |v| (a slab of that
  // width separates them), so no pair is nearer. Checked on the vertex-face pairs' best and after each edge
  // pair that improves it; where surfaces run parallel most pairs end early. Ranges taken about onA, so the
  // rounding is relative to the triangles' size, not their distance from the origin.
  auto proven = [&] {
    if (!(best.squaredDistance > 0 && best.squaredDistance < std::numeric_limits<double>::infinity())) return false;
    const Vec3 v = best.onB - best.onA, o = best.onA;
    const double aHi = std::max({dot(v, a0 - o), dot(v, a1 - o), dot(v, a2 - o)});
    const double bLo = std::min({dot(v, b0 - o), dot(v, b1 - o), dot(v, b2 - o)});
    return bLo - aHi >= best.squaredDistance * (1 - 1e-12);  // (bLo - aHi) / |v| >= |v| (1 - 1e-12)
  };
  if (proven()) return best;
  double s, t;
  Vec3 c1, c2;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double d = closestSegmentSegment(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3], s, t, c1, c2);
      if (d < best.squaredDistance) {
        best = {d, c1, c2};
        if (proven()) return best;
      }
    }
  return best;
}

}  // namespace reamsim
