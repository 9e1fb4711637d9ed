#pragma once
// The bone side of collision detection, kept in sync with the document's BoneState: a TriangleBvh over the
// state's triangle slots plus the five queries. This is the object the reaming loop and a haptic thread
// hold; see docs/COLLISION.md for how ReamController should wire it.
//
// Keeping it in sync after a cut (no rebuild):
//  - engines that produce a MeshDelta: applyDelta(next, delta, placement) — O(delta log n);
//  - engines that give removed/added slots: update(next, removed, added);
//  - engines that only give a new state (their own, or BoneState::commitByDiff): syncTo(next) — the slots
//    that differ from the state the tree last followed (BoneState::changedTriangleSlots: unchanged chunks
//    are skipped by identity), then the same local update. A collider built from a mesh has no state yet
//    and diffs against the tree's own triangles, O(slots).
#include <cstdint>
#include <optional>
#include <vector>

#include "reamsim/collision/BvhRayCast.h"
#include "reamsim/collision/DistanceQuery.h"
#include "reamsim/collision/FirstContact.h"
#include "reamsim/collision/OverlapQuery.h"
#include "reamsim/collision/PenetrationQuery.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/core/MeshDelta.h"

namespace reamsim {

// Slots whose triangle differs between what `bvh` holds and `next` (a slot whose corners changed is both):
// O(slots), for a tree not built from a BoneState (BoneCollider::changesTo is the fast way).
SlotChanges diffSlots(const TriangleBvh& bvh, const BoneState& next);

// Every directed edge has exactly one opposite edge (vertex indices): a closed, consistently oriented surface.
bool isClosedSurface(const TriangleMesh& mesh);

class BoneCollider {
 public:
  // `closed` is computed from the state's connectivity once; cuts are assumed to keep it.
  explicit BoneCollider(const BoneState& state);
  explicit BoneCollider(const TriangleMesh& mesh);  // slot = triangle index

  const TriangleBvh& bvh() const { return bvh_; }
  bool closed() const { return closed_; }
  double buildMilliseconds() const { return buildMs_; }

  BvhUpdateStats applyDelta(const BoneState& next, const MeshDelta& delta, const DeltaPlacement& placement);
  BvhUpdateStats update(const BoneState& next, const std::vector<std::uint32_t>& removedSlots,
                        const std::vector<std::uint32_t>& addedSlots);
  BvhUpdateStats syncTo(const BoneState& next);
  // The slots syncTo(next) would remove and insert.
  SlotChanges changesTo(const BoneState& next) const;

  // Query 1.
  OverlapResult overlap(const ReamerModel& reamer, const RigidTransform& pose,
                        OverlapMode mode = OverlapMode::AllTouchedFaces) const {
    return queryOverlap(bvh_, reamer, pose, mode, closed_);
  }
  // Query 2.
  DistanceResult faceDistance(const ReamerModel& reamer, const RigidTransform& pose,
                              double maxDistanceMm = std::numeric_limits<double>::infinity()) const {
    return queryFaceDistance(bvh_, reamer, pose, maxDistanceMm);
  }
  // Query 3.
  FirstContactResult firstContact(const ReamerModel& reamer, const RigidTransform& from, const RigidTransform& to) const {
    return queryFirstContact(bvh_, reamer, from, to);
  }
  // Query 4.
  std::optional<MeshHit> firstHit(const Vec3& origin, const Vec3& dir, Culling culling = Culling::None) const {
    return reamsim::firstHit(bvh_, origin, dir, culling);
  }
  std::vector<MeshHit> allHits(const Vec3& origin, const Vec3& dir, Culling culling = Culling::None) const {
    return reamsim::allHits(bvh_, origin, dir, culling);
  }
  // Query 5.
  PenetrationResult axialPenetration(const ReamerModel& reamer, const RigidTransform& pose) const {
    return queryAxialPenetration(bvh_, reamer, pose, closed_);
  }

 private:
  TriangleBvh bvh_;
  std::optional<BoneState> followed_;  // the state the tree holds (shares storage with the document's)
  bool closed_ = false;
  double buildMs_ = 0;
};

}  // namespace reamsim
