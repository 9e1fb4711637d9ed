#include "reamsim/ream/ReamStep.h"

#include <chrono>
#include <stdexcept>
#include <string>

namespace reamsim {

CutLogEntry commitReamStep(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log, AlertNode* alerts,
                           ReamComputation& c, std::size_t stepIndex, const CommitOptions& options) {
  if (bone.currentRevision() != c.baseRevision)
    throw std::logic_error("commitReamStep: the bone changed since the step was computed");
  Document::BatchScope batch(document);
  reamer.setPose(c.pose);

  CutLogEntry e;
  e.stepIndex = stepIndex;
  e.timeUnixMs = std::chrono::duration_cast<std::chrono::milliseconds>(
                     std::chrono::system_clock::now().time_since_epoch())
                     .count();
  e.pose = c.pose;
  e.note = options.note;
  // The reamer the step was computed with (the node's may have changed since, e.g. while it ran).
  const ReamerSpec& used = c.reamer ? *c.reamer : reamer.spec();
  e.reamer = used.name;
  e.reamerDiameterMm = used.diameterMm;
  if (!used.isFlat()) e.reamerSphereRadiusMm = used.sphereRadiusMm;
  e.boxesOverlap = c.contact.boxesOverlap;
  e.minDistanceMm = c.contact.minDistanceMm;
  e.contactPoint = c.contact.contactPoint;
  if (c.contact.alongMove && c.contact.alongMove->reached) {
    e.moveContactT = c.contact.alongMove->t;
    e.moveContactPoint = c.contact.alongMove->point;
  }
  e.cumulativeMm3 = log.cumulativeMm3();
  e.cutMs = c.cut.milliseconds;
  if (c.cut.changed && c.next) {
    e.contact = true;
    e.removedMm3 = c.cut.removedMm3;
    e.cumulativeMm3 += e.removedMm3;
    e.boneStateId = bone.commit(std::move(*c.next), "cut " + std::to_string(stepIndex));
    c.next.reset();
  }
  if (options.initialVolumeMm3) e.cumulativeMm3 = *options.initialVolumeMm3 - bone.current().volume();
  e.faces = bone.current().liveTriangleCount();
  if (options.logEveryStep || e.contact) log.append(e);

  if (alerts) {
    std::vector<Alert> list;
    if (e.boxesOverlap) list.push_back({AlertKind::BoundsOverlap, reamer.id(), bone.id(), e.minDistanceMm});
    if (e.contact || c.contact.contact)
      list.push_back({AlertKind::Contact, reamer.id(), bone.id(), c.contact.penetrating ? 0.0 : e.minDistanceMm});
    alerts->setAlerts(std::move(list));
  }
  return e;
}

}  // namespace reamsim
