#include "reamsim/ream/ReamController.h"

#include <cmath>
#include <stdexcept>

namespace reamsim {
namespace {

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

ReamController::ReamController(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log,
                               AlertNode* alerts)
    : document_(document), bone_(bone), reamer_(reamer), log_(log), alerts_(alerts) {
  if (!reamer_.cuttingVolume()) throw std::invalid_argument("the reamer has no cutting volume");
  localFaceVertices_ = forwardFacingVertices(*reamer_.cuttingVolume());
  syncEngineWithBone();
}

ReamController::~ReamController() = default;

// The engine keeps exact coordinates between cuts; if the document's bone changed underneath (undo,
// a new import), it restarts from the document's state.
void ReamController::syncEngineWithBone() {
  if (engine_ && engineRevision_ == bone_.currentRevision()) return;
  engine_ = std::make_unique<ReferenceSubtractor>(bone_.current().toMesh());
  engineRevision_ = bone_.currentRevision();
}

ReamStepOutcome ReamController::moveTo(const Pose& pose) {
  syncEngineWithBone();
  ReamStepOutcome out;
  Document::BatchScope batch(document_);
  reamer_.setPose(pose);
  const RigidTransform toBone = toTransform(pose);
  const TriangleMesh tool = transformed(*reamer_.cuttingVolume(), toBone);
  std::vector<Vec3> probes;
  probes.reserve(localFaceVertices_.size());
  for (const Vec3& p : localFaceVertices_) probes.push_back(toBone.apply(p));

  const TriangleMesh boneMesh = bone_.current().toMesh();
  const double stepMm = log_.empty() ? 0.0 : norm(pose.tip - log_.entries().back().pose.tip);
  out.contact = thesisContactQuery(boneMesh, bone_.current().bounds(), tool, probes, pose.axis, stepMm);

  CutLogEntry& e = out.entry;
  e.stepIndex = steps_++;
  e.pose = pose;
  e.boxesOverlap = out.contact.boxesOverlap;
  e.minDistanceMm = out.contact.minDistanceMm;
  e.contactPoint = out.contact.contactPoint;
  e.cumulativeMm3 = log_.empty() ? 0.0 : log_.entries().back().cumulativeMm3;
  if (out.contact.boxesOverlap) {
    out.cut = engine_->subtract(tool);
    e.cutMs = out.cut.milliseconds;
    if (out.cut.changed) {
      e.contact = true;
      e.removedMm3 = out.cut.removedMm3;
      e.cumulativeMm3 += e.removedMm3;
      out.volumeBookkeepingError =
          std::abs(out.cut.removedMm3 - (out.cut.volumeBeforeMm3 - out.cut.volumeAfterMm3));
      engineRevision_ = bone_.commit(BoneState::commitByDiff(bone_.current(), engine_->mesh()),
                                     "cut " + std::to_string(e.stepIndex));
      e.boneStateId = engineRevision_;
    }
  }
  e.faces = bone_.current().liveTriangleCount();
  log_.append(e);

  if (alerts_) {
    std::vector<Alert> alerts;
    if (e.boxesOverlap) alerts.push_back({AlertKind::BoundsOverlap, reamer_.id(), bone_.id(), e.minDistanceMm});
    if (e.contact) alerts.push_back({AlertKind::Contact, reamer_.id(), bone_.id(), 0.0});
    alerts_->setAlerts(std::move(alerts));
  }
  return out;
}

BoneInvariants ReamController::checkBone() const { return engine_->checkInvariants(); }

}  // namespace reamsim
