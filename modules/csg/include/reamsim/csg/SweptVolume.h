#pragma once
// The volume a reamer's cutting solid sweeps between two poses, for cuts that must leave no ridge when the
// reamer moves further than its own size between two computed steps (a fast hand move, a coarse plan).
//
// For a translation (same orientation at both poses) the volume a convex solid sweeps is exactly the convex
// hull of its two placements; every hull vertex is a placed vertex, so nothing is approximated. Rotations
// are not swept here (their swept volume is not a hull): callers cut the end pose's solid then.
#include "reamsim/core/Pose.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Closed mesh whose vertices all lie on or behind every face's plane (within a relative tolerance).
bool isConvexSolid(const TriangleMesh& closedMesh, double relativeTolerance = 1e-9);

// Convex hull of `convexSolidLocal` placed at `from` and at `to` (CGAL convex_hull_3, exact predicates),
// triangulated and outward. Throws std::invalid_argument when the two rotations differ.
TriangleMesh sweptByTranslation(const TriangleMesh& convexSolidLocal, const RigidTransform& from,
                                const RigidTransform& to);

}  // namespace reamsim
