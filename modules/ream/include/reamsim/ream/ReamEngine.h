#pragma once
// The half of the reaming loop that may run off the UI thread: the collision query and the Boolean, on
// a cutting engine this object owns. It never touches the Document (single-threaded by contract);
// commitReamStep (ReamStep.h) applies its result to the document on the document's thread.
//
// Threading: one call at a time (compute on a worker, adopt on the UI thread while no compute runs).
// BoneState values are immutable, so the caller may hand the current state to a worker.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "reamsim/core/BoneState.h"
#include "reamsim/core/Pose.h"
#include "reamsim/ream/ReamBackends.h"

namespace reamsim {

struct ReamComputation {
  Pose pose;
  std::uint64_t baseRevision = 0;  // bone revision the step was computed against
  ContactResult contact;
  bool contactChecked = false;     // false: no collision backend, nothing was queried
  ReferenceCut cut;                // cut.changed: `next` holds the bone after the cut
  bool swept = false;              // the cut subtracted the volume swept from the previous pose
  int sweepCuts = 0;               // swept: the Booleans it took (1 for a translation, the placements of a turn)
  bool sweptPastBone = false;      // a translation the first-contact query shows missed the bone: nothing swept
  std::optional<BoneState> next;
  std::optional<ReamerSpec> reamer;  // what the step's cutting volume was built from, when the engine knows
  double volumeBookkeepingError = 0;  // |removed − (V_before − V_after)|
  // Where the step's time went (ms): the collision query (with the collider following the last cut), the
  // Boolean as the cutting engine reports it, and turning the cut into the next BoneState.
  struct Times {
    double contact = 0, cut = 0, state = 0;
  } times;
};

// Thrown by ReamEngine::compute when its stop flag is up before a Boolean: the step is abandoned whole
// (a swept turn is a chain of Booleans, and the document never sees part of one), and the next compute
// restarts the cutter from the bone it is given, as after an undo.
struct ReamCancelled : std::runtime_error {
  ReamCancelled() : std::runtime_error("step cancelled") {}
};

// What another thread can do to, and see of, a running compute: raise `stop` to abandon the step before
// its next Boolean, read how many of its Booleans are done (a swept turn has tens of them).
struct StepControl {
  std::atomic<bool> stop{false};
  std::atomic<int> booleansDone{0};
  std::atomic<int> booleansTotal{0};  // 0 until the step knows (after its collision query)
};

class ReamEngine {
 public:
  // `contact` may be null (no collision: nothing is cut) and `cut` empty (collision and alerts only).
  // `spec`: what the cutting volume was built from, when known (a parametric reamer's collision queries
  // then use its ideal solid; see ReamerModel::fromCuttingVolume).
  ReamEngine(std::shared_ptr<const TriangleMesh> cuttingVolumeLocal, std::unique_ptr<ContactBackend> contact,
             CutBackendFactory cut, std::optional<ReamerSpec> spec = std::nullopt);
  ~ReamEngine();

  // Builds the cutting engine for this bone state now (otherwise the first compute does). Throws what
  // the cut backend throws for a bone it cannot cut (e.g. an open surface).
  void prepare(const BoneState& bone, std::uint64_t revision);
  // One step at `pose`; stepMm is the tip travel since the previous step (grows the broad phase).
  // `sweptFrom`: where the reamer was before this step, when it got here by moving (not placed there): a
  // translation with a sideways part cuts the whole volume swept between the two poses (SweptVolume.h), so
  // a long move leaves no ridge; a turn is cut in sub-steps along it (TurnPath), one Boolean each,
  // reported as one step. Throws std::runtime_error when a Boolean fails; the engine then resyncs (the
  // document never sees a partly cut turn). `control` (see StepControl) is read before each Boolean: its
  // stop raised, the step throws ReamCancelled, so a long swing stops within one Boolean.
  ReamComputation compute(const BoneState& bone, std::uint64_t revision, const Pose& pose, double stepMm,
                          const Pose* sweptFrom = nullptr, StepControl* control = nullptr);
  // How far the reamer can advance from `start` along its axis, up to maxMm, before its cutting solid first
  // touches `bone` (0: touching already; nullopt: nothing within maxMm): the start of "ream to depth". Asks
  // the contact engine's own structure, which follows the bone from cut to cut, so the search costs a query
  // rather than a tree built for it (~0.6 s at 400k faces; the free advanceToContactMm, used by engines
  // without an exact motion query). A call like compute: one at a time.
  std::optional<double> advanceToContactMm(const BoneState& bone, std::uint64_t revision, const Pose& start, double maxMm);
  // Whether the cutting solid at `pose` touches `bone`'s surface (its first contact along the axis is at once),
  // asked of the contact engine's own structure: fast (the first contact's start test, bounded by the ideal
  // solid), but blind to a solid wholly inside a closed bone or a fragment wholly inside the solid. nullopt when
  // the engine has no exact motion query (nothing to ask it without building a tree per call). A call like
  // compute: one at a time.
  std::optional<bool> touchesAt(const BoneState& bone, std::uint64_t revision, const Pose& pose);
  // Whether it overlaps `bone` at all (ContactBackend::overlapsAt: the surface, a fragment inside the solid, or
  // the solid inside a closed bone): what a placement there would cut. Slower than touchesAt where the solid is
  // near the bone and clear of it (~0.2 ms at 400k faces: every bone triangle in the solid's box is asked).
  std::optional<bool> overlapsAt(const BoneState& bone, std::uint64_t revision, const Pose& pose);
  // The `next` of the last compute was committed to the bone history as `revision`.
  void adopt(std::uint64_t revision);
  // Another reamer (sequential reaming with growing sizes): the bone's collision structure and the cutter's exact
  // coordinates are kept, where a new engine would build them again from the bone (0.2–0.45 s at 400k faces).
  // Between computes, as adopt.
  void setReamer(std::shared_ptr<const TriangleMesh> cuttingVolumeLocal, std::optional<ReamerSpec> spec);

  // How far a point of the cutting solid may move within one sub-step of a turning move (docs/CSG.md,
  // "Swept cutting"). A chain of placements leaves ridges of about travel² / (8 ρ), ρ the surface's radius
  // of curvature (0.5 mm: ~1 µm on a glenoid reamer's cap, 3 µm at a 20 mm flat reamer's rim, below the
  // 7 µm of its own facets), so a turn that moves no point further is cut at its end pose alone. Hulls at
  // a fixed orientation, for turns with a sideways travel, err to first order in the sub-step's angle
  // (measured: 0.3 % of a 10 degree swing's removed volume at 0.1 mm), so their sub-steps are finer.
  struct TurnTravel {
    double placementMm = 0.5;
    double hullMm = 0.1;
  };
  void setTurnTravel(TurnTravel t) { turnTravel_ = t; }
  // Whether a translation that missed the bone (ReamComputation::sweptPastBone) skips its swept hull (on by
  // default; off only to measure what the skip saves: `bench cut --loop`).
  void setSkipMissedSweeps(bool on) { skipMissedSweeps_ = on; }

  bool canCollide() const { return contact_ != nullptr; }
  bool canCut() const { return static_cast<bool>(cutFactory_); }
  BoneInvariants checkBone() const;  // costly; precondition: prepared or computed at least once
  const std::shared_ptr<const TriangleMesh>& cuttingVolume() const { return cuttingVolume_; }

 private:
  void sync(const BoneState& bone, std::uint64_t revision);
  void deriveFromReamer();  // the figures read off the cutting volume (face vertices, convexity, reach)
  // What a move from `from` to `to` sweeps, as the tools to subtract in order; empty: cut the end pose.
  std::vector<TriangleMesh> sweepTools(const RigidTransform& from, const RigidTransform& to) const;
  const TriangleMesh* meshFor(const BoneState& bone, std::uint64_t revision);

  std::shared_ptr<const TriangleMesh> cuttingVolume_;
  std::optional<ReamerSpec> spec_;
  std::vector<Vec3> localFaceVertices_;
  bool convexSolid_ = false;  // swept volumes are hulls: convex cutting solids only
  double axialLength_ = 0;    // extent of the cutting solid along its axis
  double solidRadius_ = 0;    // farthest point of the cutting solid from the tip (a turn's arcs)
  TurnTravel turnTravel_;
  bool skipMissedSweeps_ = true;
  std::unique_ptr<ContactBackend> contact_;
  CutBackendFactory cutFactory_;
  std::unique_ptr<CutBackend> cutter_;
  TriangleMesh boneMesh_;              // the bone as a mesh, for a contact backend that needsMesh()
  std::uint64_t meshRevision_ = 0;     // revision of boneMesh_ (0: none)
  bool meshAwaitsAdopt_ = false;       // boneMesh_ is the last compute's result, not yet committed
  std::uint64_t cutterRevision_ = 0;   // revision the cutter holds (0: none)
  bool pendingAdopt_ = false;          // the cutter is one cut ahead of any committed revision
};

// Vertices of a cutting volume that face the feed direction (+Z): the probes of the thesis's rays.
std::vector<Vec3> forwardFacingVertices(const TriangleMesh& cuttingVolume);

}  // namespace reamsim
