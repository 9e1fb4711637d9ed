#pragma once
// The two engines the reaming loop uses, as small interfaces so the GUI can load them from plugins.
// Collision: the BVH queries (default) or the thesis's rays (the reference). Cutting: the local exact engine
// (LocalCutBackend.h) or CGAL whole-mesh exact corefinement (the reference).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "reamsim/collision/ContactResult.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/mesh/Bounds.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Everything a contact engine may use for one query; all in bone coordinates unless said otherwise.
struct ContactInput {
  const BoneState& bone;
  std::uint64_t revision;        // changes whenever `bone` does: engines that keep a structure resync on it
  const TriangleMesh* boneMesh;  // `bone` as a plain mesh when the backend needsMesh() (O(bone) to make), else null
  const Bounds& boneBounds;
  // Reamer-local; the same object every call until the reamer changes (ReamEngine::setReamer), when it is another
  // object: backends that derive a model from it key that on the object.
  const std::shared_ptr<const TriangleMesh>& cuttingVolumeLocal;
  const ReamerSpec* reamerSpec;  // the spec the volume was built from, when known (null: a solid alone)
  const RigidTransform& pose;    // reamer-local -> bone
  const TriangleMesh& tool;      // the cutting volume placed at `pose`
  const std::vector<Vec3>& probes;  // forward-facing cutting-face vertices placed at `pose` (thesis rays)
  Vec3 feedAxis;                 // unit
  double stepMm;                 // tip travel since the previous query
  // The pose before this step when the reamer moved here (not placed): exact engines then also say where
  // the move first met the bone (ContactResult::alongMove). Null: no move to follow.
  const RigidTransform* movedFrom = nullptr;
};

class ContactBackend {
 public:
  virtual ~ContactBackend() = default;
  virtual ContactResult query(const ContactInput& input) = 0;
  virtual bool needsMesh() const { return false; }  // wants ContactInput::boneMesh (the thesis's rays)
  // The exact first contact of the cutting solid moving from `from` to `to` (reamer-local -> bone), on the
  // engine's own structure brought up to `bone` (so "ream to depth" searches without building one). Engines
  // without an exact motion query return nullopt (the caller then builds one: advanceToContactMm).
  virtual std::optional<MoveContact> firstContactAlong(const BoneState& /*bone*/, std::uint64_t /*revision*/,
                                                       const std::shared_ptr<const TriangleMesh>& /*cuttingVolumeLocal*/,
                                                       const ReamerSpec* /*reamerSpec*/, const RigidTransform& /*from*/,
                                                       const RigidTransform& /*to*/) {
    return std::nullopt;
  }
  // Whether the cutting solid at `pose` overlaps the bone: touches its surface, holds some of it (a fragment
  // wholly inside the solid), or lies wholly inside a closed bone. What placing the reamer there would cut.
  // Engines without an exact query return nullopt.
  virtual std::optional<bool> overlapsAt(const BoneState& /*bone*/, std::uint64_t /*revision*/,
                                         const std::shared_ptr<const TriangleMesh>& /*cuttingVolumeLocal*/,
                                         const ReamerSpec* /*reamerSpec*/, const RigidTransform& /*pose*/) {
    return std::nullopt;
  }
};

// A cutting engine holding one bone (it may keep its own exact representation between cuts).
class CutBackend {
 public:
  virtual ~CutBackend() = default;
  virtual ReferenceCut subtract(const TriangleMesh& toolInBoneCoords) = 0;
  virtual TriangleMesh mesh() const = 0;
  // The bone after the last cut as a state derived from the one the engine was built from (its slots kept,
  // its unchanged chunks shared): committed as is, O(cut). Null for an engine that only has a whole mesh
  // (the loop then diffs it against the previous state, O(bone)).
  virtual const BoneState* state() const { return nullptr; }
  virtual BoneInvariants checkInvariants() const = 0;
  // The reamer's cutting solid (its own frame) that every tool of this engine is made from, placed or swept:
  // an engine may set tolerances from it (the local engine's clean-up bound follows its facet sag).
  virtual void setCuttingSolid(const TriangleMesh& /*solidLocal*/) {}
};
// Builds an engine for a bone state; throws std::invalid_argument for a bone it cannot cut.
using CutBackendFactory = std::function<std::unique_ptr<CutBackend>(const BoneState& bone)>;

std::unique_ptr<ContactBackend> makeThesisContactBackend();
// Exact queries on a BVH that follows the bone's cuts locally (BoneCollider): overlap with the touched faces,
// the cutting face's minimum distance and, if asked, the axial penetration depth (the costliest query:
// milliseconds at 400k faces; the GUI does not show it and leaves it out).
std::unique_ptr<ContactBackend> makeBvhContactBackend(bool axialDepth = true);
CutBackendFactory referenceCutBackendFactory();

}  // namespace reamsim
