#pragma once
// Moeller-Trumbore ray/triangle intersection.
//
// Epsilon policy (all documented constants are below):
//  * Parallel / degenerate: |det|, det = -dir . (e1 x e2) with e1 = b - a, e2 = c - a, is compared with
//    kParallelEpsilon * |dir| * |e1| * |e2| (scale-free: the sine of the ray/plane angle times the sine of a
//    triangle angle). Below it the ray is treated as parallel and misses, including a ray lying IN the
//    triangle's plane (coplanar): the neighbouring non-coplanar triangles report the crossing instead.
//    Zero-area triangles fall under the same rule and never hit.
//  * Edges and vertices: barycentric bounds are widened by kBarycentricEpsilon (u >= -eps, v >= -eps,
//    u + v <= 1 + eps), so a ray through an edge or vertex is never lost to rounding. The price is that a
//    ray through a shared edge/vertex hits every adjacent triangle; MeshRayCast's allHits() dedupes those.
//  * Ray start: hits with t < -kRayStartEpsilon are behind the origin and rejected; t in
//    [-kRayStartEpsilon, 0) is clamped to 0 (an origin on the surface hits it at t = 0). t is in units of
//    |dir| (mm for a unit direction).
//  * Back-face culling: with Culling::BackFaces only triangles the ray enters through the front hit
//    (dir . normal < 0, normal = (b - a) x (c - a), i.e. counter-clockwise seen from outside).
#include <optional>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

inline constexpr double kParallelEpsilon = 1e-12;
inline constexpr double kBarycentricEpsilon = 1e-9;
inline constexpr double kRayStartEpsilon = 1e-9;

enum class Culling { None, BackFaces };

struct RayHit {
  double t = 0;               // hit point = origin + t * dir
  double u = 0, v = 0;        // barycentric: point = (1-u-v) a + u b + v c
  bool frontFacing = true;    // the ray enters through the triangle's front (dir . normal < 0)
};

std::optional<RayHit> intersectRayTriangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b,
                                           const Vec3& c, Culling culling = Culling::None);

}  // namespace reamsim
