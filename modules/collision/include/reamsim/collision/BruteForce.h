#pragma once
// Brute-force references for the BVH queries: every bone triangle against every reamer triangle, no
// hierarchy (only a per-pair box reject). They use the same exact leaf predicates, so a disagreement with
// the BVH queries means the hierarchy (build, update, traversal or pruning) lost a pair. Cost is
// O(bone x reamer) per query: for tests and cross-checks, never for the reaming loop.
#include "reamsim/collision/DistanceQuery.h"
#include "reamsim/collision/FirstContact.h"
#include "reamsim/collision/OverlapQuery.h"
#include "reamsim/collision/PenetrationQuery.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

OverlapResult bruteForceOverlap(const TriangleMesh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                bool boneClosed = false);
DistanceResult bruteForceFaceDistance(const TriangleMesh& bone, const ReamerModel& reamer, const RigidTransform& pose);
FirstContactResult bruteForceFirstContact(const TriangleMesh& bone, const ReamerModel& reamer,
                                          const RigidTransform& from, const RigidTransform& to);
PenetrationResult bruteForceAxialPenetration(const TriangleMesh& bone, const ReamerModel& reamer,
                                             const RigidTransform& pose, bool boneClosed = false);

}  // namespace reamsim
