// The BVH contact engine for the reaming loop: a BoneCollider that follows the bone's cuts with local
// updates (a cut touches a few thousand slots; the tree is not rebuilt), and a ReamerModel built once from
// the reamer's cutting volume.
#include <memory>
#include <optional>

#include "reamsim/collision/BoneCollider.h"
#include "reamsim/collision/BroadPhase.h"
#include "reamsim/ream/ReamBackends.h"

namespace reamsim {
namespace {

class BvhContactBackend final : public ContactBackend {
 public:
  explicit BvhContactBackend(bool axialDepth) : axialDepth_(axialDepth) {}

  std::optional<MoveContact> firstContactAlong(const BoneState& bone, std::uint64_t revision,
                                               const std::shared_ptr<const TriangleMesh>& cuttingVolumeLocal,
                                               const ReamerSpec* reamerSpec, const RigidTransform& from,
                                               const RigidTransform& to) override {
    syncReamer(cuttingVolumeLocal, reamerSpec);
    syncBone(bone, revision);
    return moveContact(collider_->firstContact(*reamer_, from, to));
  }

  std::optional<bool> overlapsAt(const BoneState& bone, std::uint64_t revision,
                                 const std::shared_ptr<const TriangleMesh>& cuttingVolumeLocal,
                                 const ReamerSpec* reamerSpec, const RigidTransform& pose) override {
    syncReamer(cuttingVolumeLocal, reamerSpec);
    syncBone(bone, revision);
    return collider_->overlap(*reamer_, pose, OverlapMode::AnyContact).overlap;
  }

  ContactResult query(const ContactInput& in) override {
    syncReamer(in.cuttingVolumeLocal, in.reamerSpec);
    syncBone(in.bone, in.revision);

    ContactResult r;
    Bounds reamerBox = computeBounds(in.tool);
    r.boxesOverlap = boundsOverlap(in.boneBounds, reamerBox.expanded(in.stepMm));
    // The distance is cheap on the tree, so it is always known (the status bar shows it live). Successive
    // poses are close: the tracker answers most of them from the triangles its last search found near the
    // face, exactly (FaceDistanceTracker); a cut or another reamer makes it search afresh.
    const DistanceResult distance = distanceTracker_.query(collider_->bvh(), *reamer_, in.pose);
    if (distance.found) {
      r.minDistanceMm = distance.distanceMm;
      r.contactPoint = distance.onBone;  // the closest point, or where the cutting face meets the bone
    }
    if (in.movedFrom) {
      // The move as a whole: exact, so a fast move through thin bone is seen, and one that passes beside
      // the bone is known to miss it (the loop then skips its swept hull).
      r.alongMove = moveContact(collider_->firstContact(*reamer_, *in.movedFrom, in.pose));
    }
    if (!r.boxesOverlap) {
      r.solidOverlapsBone = false;  // disjoint boxes
      return r;
    }
    const OverlapResult overlap = collider_->overlap(*reamer_, in.pose);
    r.solidOverlapsBone = overlap.overlap;
    r.touchedFaces = overlap.touchedSlots.size();
    if (overlap.overlap) {
      r.penetrating = true;
      r.minDistanceMm = 0;
      if (axialDepth_) r.penetrationDepthMm = collider_->axialPenetration(*reamer_, in.pose).depthMm;
    }
    r.contact = r.penetrating;  // exact: touching or entering (not the thesis's "gap within one step")
    return r;
  }

 private:
  static MoveContact moveContact(const FirstContactResult& first) {
    MoveContact m;
    m.reached = first.hit;
    if (first.hit) {
      m.t = first.t;
      m.point = first.point;
      m.normal = first.normal;
    }
    return m;
  }

  void syncReamer(const std::shared_ptr<const TriangleMesh>& solid, const ReamerSpec* spec) {
    if (solid == reamerSource_) return;
    reamer_ = std::make_unique<ReamerModel>(ReamerModel::fromCuttingVolume(*solid, spec));
    reamerSource_ = solid;
  }

  // A cut changes a small part of the slots: follow it locally (the states share their unchanged chunks,
  // so finding the changed slots costs microseconds). A different bone (import, undo across many cuts)
  // changes most of them: build afresh, which is faster then and re-derives whether it is closed.
  void syncBone(const BoneState& bone, std::uint64_t revision) {
    if (collider_ && revision == revision_) return;
    if (collider_) {
      const SlotChanges changes = collider_->changesTo(bone);
      if (changes.removed.size() + changes.added.size() < bone.liveTriangleCount() / 2) {
        collider_->update(bone, changes.removed, changes.added);
        revision_ = revision;
        return;
      }
    }
    collider_ = std::make_unique<BoneCollider>(bone);
    revision_ = revision;
  }

  std::shared_ptr<const TriangleMesh> reamerSource_;
  std::unique_ptr<ReamerModel> reamer_;
  std::unique_ptr<BoneCollider> collider_;
  FaceDistanceTracker distanceTracker_;  // keyed on the tree's and the face's revisions: resets itself
  std::uint64_t revision_ = 0;
  bool axialDepth_;
};

}  // namespace

std::unique_ptr<ContactBackend> makeBvhContactBackend(bool axialDepth) {
  return std::make_unique<BvhContactBackend>(axialDepth);
}

}  // namespace reamsim
