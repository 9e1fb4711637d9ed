#pragma once
// Closest points on triangles and segments: plain geometry, shared by the collision queries and the
// reamed-surface measure (modules/tools), which cannot depend on each other.
#include "reamsim/mesh/Vec3.h"

namespace reamsim {

// Which feature of triangle abc a closest point lies on.
enum class TriangleRegion { Face, VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA };

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5), and optionally its
// feature (for pseudo-normal inside tests).
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                            TriangleRegion* region = nullptr);

// Closest points c1 = p1 + s (q1 - p1), c2 = p2 + t (q2 - p2) of two segments; returns |c1 - c2|^2.
double closestSegmentSegment(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, double& s, double& t,
                             Vec3& c1, Vec3& c2);

}  // namespace reamsim
