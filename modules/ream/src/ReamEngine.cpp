#include "reamsim/ream/ReamEngine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "reamsim/csg/SweptVolume.h"
#include "reamsim/ream/Approach.h"

namespace reamsim {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

TriangleMesh transformed(const TriangleMesh& local, const RigidTransform& t) {
  TriangleMesh out = local;
  for (Vec3& p : out.vertices) p = t.apply(p);
  return out;
}

}  // namespace

std::vector<Vec3> forwardFacingVertices(const TriangleMesh& m) {
  std::vector<Vec3> normal(m.vertices.size());
  for (const Triangle& t : m.triangles) {
    const Vec3 area = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    for (std::uint32_t v : t) normal[v] += area;
  }
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (normal[i].z > 0) out.push_back(m.vertices[i]);
  return out;
}

ReamEngine::ReamEngine(std::shared_ptr<const TriangleMesh> cuttingVolumeLocal, std::unique_ptr<ContactBackend> contact,
                       CutBackendFactory cut, std::optional<ReamerSpec> spec)
    : cuttingVolume_(std::move(cuttingVolumeLocal)),
      spec_(std::move(spec)),
      contact_(std::move(contact)),
      cutFactory_(std::move(cut)) {
  deriveFromReamer();
}

void ReamEngine::deriveFromReamer() {
  if (!cuttingVolume_) throw std::invalid_argument("the reamer has no cutting volume");
  localFaceVertices_ = forwardFacingVertices(*cuttingVolume_);
  convexSolid_ = isConvexSolid(*cuttingVolume_);
  const Bounds local = computeBounds(*cuttingVolume_);
  axialLength_ = local.max.z - local.min.z;  // reamer-local: the feed axis is +z
  solidRadius_ = 0;
  for (const Vec3& p : cuttingVolume_->vertices) solidRadius_ = std::max(solidRadius_, norm(p));
}

void ReamEngine::setReamer(std::shared_ptr<const TriangleMesh> cuttingVolumeLocal, std::optional<ReamerSpec> spec) {
  if (!cuttingVolumeLocal) throw std::invalid_argument("the reamer has no cutting volume");
  cuttingVolume_ = std::move(cuttingVolumeLocal);
  spec_ = std::move(spec);
  deriveFromReamer();
  // The contact engine takes the new volume from the next query's input (it is another object); the cutter goes
  // on from its exact coordinates with the new tool.
  if (cutter_) cutter_->setCuttingSolid(*cuttingVolume_);
}

ReamEngine::~ReamEngine() = default;

void ReamEngine::prepare(const BoneState& bone, std::uint64_t revision) { sync(bone, revision); }

std::optional<double> ReamEngine::advanceToContactMm(const BoneState& bone, std::uint64_t revision, const Pose& start,
                                                     double maxMm) {
  if (!(maxMm > 0) || !std::isfinite(maxMm)) throw std::invalid_argument("advanceToContactMm: maxMm must be > 0");
  if (bone.empty()) return std::nullopt;
  const ReamerSpec* spec = spec_ ? &*spec_ : nullptr;
  if (contact_) {
    const auto along = contact_->firstContactAlong(bone, revision, cuttingVolume_, spec, toTransform(start),
                                                   toTransform(advancedAlongAxis(start, maxMm)));
    if (along) return along->reached ? std::optional<double>(along->t * maxMm) : std::nullopt;
  }
  return reamsim::advanceToContactMm(bone, *cuttingVolume_, start, maxMm, spec);  // builds a tree for this call
}

std::optional<bool> ReamEngine::touchesAt(const BoneState& bone, std::uint64_t revision, const Pose& pose) {
  if (bone.empty()) return false;
  if (!contact_) return std::nullopt;
  const ReamerSpec* spec = spec_ ? &*spec_ : nullptr;
  // A motion of a micrometre: its first contact at t = 0 is a touch at the pose itself.
  const auto along = contact_->firstContactAlong(bone, revision, cuttingVolume_, spec, toTransform(pose),
                                                 toTransform(advancedAlongAxis(pose, 1e-3)));
  if (!along) return std::nullopt;
  return along->reached && along->t == 0;
}

std::optional<bool> ReamEngine::overlapsAt(const BoneState& bone, std::uint64_t revision, const Pose& pose) {
  if (bone.empty()) return false;
  if (!contact_) return std::nullopt;
  return contact_->overlapsAt(bone, revision, cuttingVolume_, spec_ ? &*spec_ : nullptr, toTransform(pose));
}

// The cutter keeps exact coordinates between cuts; when the bone changed underneath (undo, a new import,
// a dropped computation) it restarts from the given state.
void ReamEngine::sync(const BoneState& bone, std::uint64_t revision) {
  if (cutFactory_ && (!cutter_ || cutterRevision_ != revision || pendingAdopt_)) {
    cutter_.reset();
    cutterRevision_ = 0;
    cutter_ = cutFactory_(bone);
    cutter_->setCuttingSolid(*cuttingVolume_);
    cutterRevision_ = revision;
  }
  if (pendingAdopt_) meshAwaitsAdopt_ = false;  // that computation was dropped: boneMesh_ is not the bone
  pendingAdopt_ = false;
}

// Only a backend that reads the whole mesh (the thesis's rays) pays for making it, once per revision.
const TriangleMesh* ReamEngine::meshFor(const BoneState& bone, std::uint64_t revision) {
  if (!contact_->needsMesh()) return nullptr;
  if (meshRevision_ != revision) {
    boneMesh_ = bone.toMesh();
    meshRevision_ = revision;
  }
  return &boneMesh_;
}

namespace {

bool sameRotation(const RigidTransform& a, const RigidTransform& b) {
  for (int i = 0; i < 9; ++i)
    if (a.rotation[i] != b.rotation[i]) return false;
  return true;
}

// Sideways travel under which a translation is cut at its end pose: all it would sweep lies within this of
// the end placement, 4x under the clean-up's per-operation deviation bound and 17x under the default reamers'
// facet sag (docs/CSG.md), and a run of such moves leaves ridges of (travel)^2 / 8R between its placements.
// (A hand-held device at rest jitters by less; each such tick swept its hull, 6-9 ms, before session 40.)
constexpr double kNegligibleSidewaysMm = 1e-3;

// A translation is swept when it moves sideways (more than kNegligibleSidewaysMm), or along the axis further
// than the solid is long (a shorter axial feed is covered by the end pose's solid: sweeping it would change
// nothing).
bool translationNeedsSweep(const RigidTransform& from, const RigidTransform& to, double axialLength) {
  const Vec3 axis = to.applyToDirection({0, 0, 1});
  const Vec3 d = to.translation - from.translation;
  const Vec3 sideways = d - axis * dot(d, axis);
  return norm(sideways) > kNegligibleSidewaysMm || std::abs(dot(d, axis)) >= axialLength;
}

// One cut's figures added to the step's: volumes before the first change and after the last.
void accumulate(ReferenceCut& total, const ReferenceCut& c) {
  total.milliseconds += c.milliseconds;
  if (!c.changed) return;
  if (!total.changed) total.volumeBeforeMm3 = c.volumeBeforeMm3;
  total.changed = true;
  total.removedMm3 += c.removedMm3;
  total.volumeAfterMm3 = c.volumeAfterMm3;
  total.facesAfter = c.facesAfter;
}

}  // namespace

std::vector<TriangleMesh> ReamEngine::sweepTools(const RigidTransform& from, const RigidTransform& to) const {
  std::vector<TriangleMesh> tools;
  if (sameRotation(from, to)) {
    if (convexSolid_ && translationNeedsSweep(from, to, axialLength_))
      tools.push_back(sweptByTranslation(*cuttingVolume_, from, to));
    return tools;
  }
  // A turn, in sub-steps along it (SweptVolume.h). A short one is covered by the end pose's solid up to
  // ridges of second order. Where the tip travels across the axis, each sub-step is the hull of that travel
  // at the sub-step's first orientation (so every pose sampled along the path is cut as it is) and the end
  // pose's solid closes the chain; a turn in place (or with a short axial feed) is a chain of placements.
  const TurnPath path(from, to);
  if (!path.isTurn()) return tools;
  const int placements = turnSubSteps(path, solidRadius_, turnTravel_.placementMm, true);
  if (placements <= 1) return tools;
  RigidTransform acrossTravel = to;
  acrossTravel.translation = from.translation;
  const bool hulls = convexSolid_ && translationNeedsSweep(acrossTravel, to, axialLength_);
  const int n = hulls ? turnSubSteps(path, solidRadius_, turnTravel_.hullMm, false) : placements;
  for (int i = 1; i <= n; ++i) {
    if (hulls) {
      const RigidTransform start = path.at(double(i - 1) / n);
      RigidTransform end = start;
      end.translation = path.at(double(i) / n).translation;
      if (translationNeedsSweep(start, end, axialLength_)) {
        tools.push_back(sweptByTranslation(*cuttingVolume_, start, end));
        if (i < n) continue;
      }
    }
    tools.push_back(transformed(*cuttingVolume_, path.at(double(i) / n)));
  }
  return tools;
}

ReamComputation ReamEngine::compute(const BoneState& bone, std::uint64_t revision, const Pose& pose, double stepMm,
                                    const Pose* sweptFrom, StepControl* control) {
  sync(bone, revision);
  ReamComputation out;
  out.pose = pose;
  out.baseRevision = revision;
  out.reamer = spec_;
  if (!contact_) return out;

  const RigidTransform toBone = toTransform(pose);
  TriangleMesh tool = transformed(*cuttingVolume_, toBone);
  std::vector<Vec3> probes;
  probes.reserve(localFaceVertices_.size());
  for (const Vec3& p : localFaceVertices_) probes.push_back(toBone.apply(p));
  const Bounds boneBounds = bone.bounds();
  const std::optional<RigidTransform> from = sweptFrom ? std::optional(toTransform(*sweptFrom)) : std::nullopt;
  const auto contactStart = std::chrono::steady_clock::now();
  out.contact = contact_->query({bone, revision, meshFor(bone, revision), boneBounds, cuttingVolume_,
                                 spec_ ? &*spec_ : nullptr, toBone, tool, probes, normalized(pose.axis), stepMm,
                                 from ? &*from : nullptr});
  out.contactChecked = true;
  out.times.contact = msSince(contactStart);

  // An exact engine says whether the cutting volume reaches the bone; with the thesis's rays the Boolean runs
  // whenever the boxes overlap, so that bone entering from the side (which the rays cannot see) is still cut.
  bool mayCut = out.contact.solidOverlapsBone ? *out.contact.solidOverlapsBone : out.contact.boxesOverlap;
  std::vector<TriangleMesh> tools;
  // A translation that the exact first-contact query shows never brought the solid onto the bone, and that
  // ends clear of it, swept past the bone: its hull (~4 ms to build) would cut nothing. Turns keep their
  // sub-steps: their chain of hulls and placements is not the query's path to the micrometre.
  const ContactResult& c = out.contact;
  out.sweptPastBone = from && sameRotation(*from, toBone) && c.alongMove && !c.alongMove->reached &&
                      c.solidOverlapsBone && !*c.solidOverlapsBone;
  if (from && !(out.sweptPastBone && skipMissedSweeps_)) tools = sweepTools(*from, toBone);
  if (!tools.empty()) {
    out.swept = true;
    out.sweepCuts = static_cast<int>(tools.size());
    // The query saw the end pose only; each swept tool is tested against the bone's box instead, and
    // those that miss it are not cut.
    tools.erase(std::remove_if(tools.begin(), tools.end(),
                               [&](const TriangleMesh& t) { return !computeBounds(t).overlaps(boneBounds); }),
                tools.end());
    mayCut = !tools.empty();
  } else {
    tools.push_back(std::move(tool));
  }
  if (mayCut && cutter_) {
    auto stopIfCancelled = [&] {
      if (control && control->stop.load(std::memory_order_relaxed)) throw ReamCancelled();
    };
    if (control) control->booleansTotal = static_cast<int>(tools.size());
    stopIfCancelled();  // before the first Boolean the cutter is still in step with `revision`
    pendingAdopt_ = true;  // from here the cutter may differ from `revision` (also if subtract throws)
    for (std::size_t i = 0; i < tools.size(); ++i) {
      if (i > 0) stopIfCancelled();
      accumulate(out.cut, cutter_->subtract(tools[i]));
      if (control) control->booleansDone = static_cast<int>(i + 1);
    }
    out.times.cut = out.cut.milliseconds;
    if (!out.cut.changed) {
      pendingAdopt_ = false;
      return out;
    }
    out.volumeBookkeepingError = std::abs(out.cut.removedMm3 - (out.cut.volumeBeforeMm3 - out.cut.volumeAfterMm3));
    const auto stateStart = std::chrono::steady_clock::now();
    if (const BoneState* state = cutter_->state()) {
      out.next = *state;  // derived from `bone` by the cut's delta: O(cut)
    } else {
      boneMesh_ = cutter_->mesh();
      meshRevision_ = 0;
      meshAwaitsAdopt_ = true;
      out.next = BoneState::commitByDiff(bone, boneMesh_);
    }
    out.times.state = msSince(stateStart);
  }
  return out;
}

void ReamEngine::adopt(std::uint64_t revision) {
  if (!pendingAdopt_) return;
  if (meshAwaitsAdopt_) meshRevision_ = revision;
  meshAwaitsAdopt_ = false;
  cutterRevision_ = revision;
  pendingAdopt_ = false;
}

BoneInvariants ReamEngine::checkBone() const {
  if (!cutter_) throw std::logic_error("ReamEngine::checkBone: no cutting engine");
  return cutter_->checkInvariants();
}

}  // namespace reamsim
