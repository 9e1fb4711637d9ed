#pragma once
// Query 4: Moeller-Trumbore ray casts through the BVH. Same per-triangle test (RayTriangle.h), same
// epsilon policy and the same crossing merge as the brute-force MeshRayCast.h, so the two agree hit for hit
// (MeshHit::triangle is the BVH slot; ties in t go to the lowest slot, as in the brute force).
#include <limits>
#include <optional>
#include <vector>

#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim {

// Nearest hit with t in [0, tMax] (t in units of |dir|), or nullopt.
std::optional<MeshHit> firstHit(const TriangleBvh& bvh, const Vec3& origin, const Vec3& dir,
                                 Culling culling = Culling::None,
                                 double tMax = std::numeric_limits<double>::infinity());

// Distinct surface crossings sorted by t (see allHits in MeshRayCast.h).
std::vector<MeshHit> allHits(const TriangleBvh& bvh, const Vec3& origin, const Vec3& dir,
                             Culling culling = Culling::None);

// Crossing parity along a fixed skew direction: true when p is inside the closed surface held by `bvh`.
// Meaningful for closed, consistently oriented surfaces only; p should not lie on the surface.
bool insideClosedSurface(const TriangleBvh& bvh, const Vec3& p);

}  // namespace reamsim
