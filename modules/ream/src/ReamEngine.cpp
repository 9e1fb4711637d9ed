#include "reamsim/ream/ReamEngine.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "reamsim/csg/SweptVolume.h"

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
  if (!cuttingVolume_) throw std::invalid_argument("the reamer has no cutting volume");
  localFaceVertices_ = forwardFacingVertices(*cuttingVolume_);
  convexSolid_ = isConvexSolid(*cuttingVolume_);
  const Bounds local = computeBounds(*cuttingVolume_);
  axialLength_ = local.max.z - local.min.z;  // reamer-local: the feed axis is +z
}

ReamEngine::~ReamEngine() = default;

void ReamEngine::prepare(const BoneState& bone, std::uint64_t revision) { sync(bone, revision); }

// The cutter keeps exact coordinates between cuts; when the bone changed underneath (undo, a new import,
// a dropped computation) it restarts from the given state.
void ReamEngine::sync(const BoneState& bone, std::uint64_t revision) {
  if (cutFactory_ && (!cutter_ || cutterRevision_ != revision || pendingAdopt_)) {
    cutter_.reset();
    cutterRevision_ = 0;
    cutter_ = cutFactory_(bone);
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

// A sweep is cut for a pure translation that moves sideways, or along the axis further than the solid is
// long (a shorter axial feed is covered by the end pose's solid: sweeping it would change nothing).
bool needsSweep(const RigidTransform& from, const RigidTransform& to, const Vec3& axis, double axialLength) {
  for (int i = 0; i < 9; ++i)
    if (from.rotation[i] != to.rotation[i]) return false;
  const Vec3 d = to.translation - from.translation;
  const Vec3 sideways = d - axis * dot(d, axis);
  return norm(sideways) > 1e-9 || std::abs(dot(d, axis)) >= axialLength;
}

}  // namespace

ReamComputation ReamEngine::compute(const BoneState& bone, std::uint64_t revision, const Pose& pose, double stepMm,
                                    const Pose* sweptFrom) {
  sync(bone, revision);
  ReamComputation out;
  out.pose = pose;
  out.baseRevision = revision;
  if (!contact_) return out;

  const RigidTransform toBone = toTransform(pose);
  TriangleMesh tool = transformed(*cuttingVolume_, toBone);
  std::vector<Vec3> probes;
  probes.reserve(localFaceVertices_.size());
  for (const Vec3& p : localFaceVertices_) probes.push_back(toBone.apply(p));
  const Bounds boneBounds = bone.bounds();
  const auto contactStart = std::chrono::steady_clock::now();
  out.contact = contact_->query(
      {bone, revision, meshFor(bone, revision), boneBounds, cuttingVolume_, spec_ ? &*spec_ : nullptr, toBone, tool, probes,
       normalized(pose.axis), stepMm});
  out.contactChecked = true;
  out.times.contact = msSince(contactStart);

  // An exact engine says whether the cutting volume reaches the bone; with the thesis's rays the Boolean runs
  // whenever the boxes overlap, so that bone entering from the side (which the rays cannot see) is still cut.
  bool mayCut = out.contact.solidOverlapsBone ? *out.contact.solidOverlapsBone : out.contact.boxesOverlap;
  if (sweptFrom && convexSolid_) {
    const RigidTransform from = toTransform(*sweptFrom);
    if (needsSweep(from, toBone, normalized(pose.axis), axialLength_)) {
      tool = sweptByTranslation(*cuttingVolume_, from, toBone);
      out.swept = true;
      // The query saw the end pose only; the sweep lies within its box grown by the travel.
      mayCut = out.contact.boxesOverlap;
    }
  }
  if (mayCut && cutter_) {
    pendingAdopt_ = true;  // from here the cutter may differ from `revision` (also if subtract throws)
    out.cut = cutter_->subtract(tool);
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
