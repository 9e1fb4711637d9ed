#pragma once
// Exact-up-to-rounding primitives shared by the queries and the brute-force references.
//
// Tolerance policy: triangles are closed sets, and "touching" counts as intersecting. A separating axis
// only separates when the gap exceeds kTouchEpsilon x |axis| x (coordinate magnitude after moving the
// origin to the first triangle), so two triangles closer than about 1e-12 of their size/offset are
// reported as touching. Tests compare against CGAL's exact predicates with that tolerance.
#include "reamsim/mesh/ClosestPoints.h"  // closestPointOnTriangle, closestSegmentSegment
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

inline constexpr double kTouchEpsilon = 1e-12;

// Separating-axis test over the 17 candidate axes (2 normals, 9 edge-edge, 6 in-plane edge normals), so
// coplanar and degenerate (zero-area) triangles are handled too.
bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                        const Vec3& b2);

struct ClosestPair {
  double squaredDistance = 0;
  Vec3 onA, onB;  // onA on triangle A, onB on triangle B (equal when they intersect)
};

// Minimum distance between two closed triangles with a closest point pair. 0 (and a common point) when
// trianglesIntersect() is true.
ClosestPair closestTriangleTriangle(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                                    const Vec3& b2);

// The same for triangles already known not to intersect: only the 15 feature pairs (6 vertex-face, 9
// edge-edge), no separating-axis test.
ClosestPair closestDisjointTriangles(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                                     const Vec3& b2);

// Squared distance between two axis-aligned boxes (0 when they overlap).
inline double boxSquaredDistance(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double g = alo[i] > bhi[i] ? alo[i] - bhi[i] : (blo[i] > ahi[i] ? blo[i] - ahi[i] : 0.0);
    d2 += g * g;
  }
  return d2;
}
inline bool boxesOverlap(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y && alo.z <= bhi.z && blo.z <= ahi.z;
}

}  // namespace reamsim
