#include "reamsim/ream/RemovalPreview.h"

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "reamsim/ream/Approach.h"

namespace reamsim {

RemovalPreview previewReamToDepth(ReamEngine& engine, const BoneState& bone, const Pose& start, double depthMm,
                                  double stepMm, double reachMm, StepControl* control) {
  if (!(depthMm > 0) || !std::isfinite(depthMm)) throw std::invalid_argument("previewReamToDepth: the depth must be positive");
  if (!(stepMm > 0) || !std::isfinite(stepMm)) throw std::invalid_argument("previewReamToDepth: the step must be positive");
  if (!(reachMm > 0)) throw std::invalid_argument("previewReamToDepth: the reach must be positive");
  if (!engine.canCollide() || !engine.canCut())
    throw std::invalid_argument("previewReamToDepth: the engine cannot collide and cut");
  // Revisions of the copy's own states, a block of its own for every call: an engine given another bone under a
  // revision it has seen would take it for the bone it holds. Far above the documents' (BoneHistory counts up from 1).
  static std::atomic<std::uint64_t> nextBlock{std::uint64_t(1) << 62};
  std::uint64_t revision = nextBlock.fetch_add(std::uint64_t(1) << 32);
  const auto stopAsked = [control] {
    if (control && control->stop) throw ReamCancelled();
  };
  stopAsked();
  RemovalPreview out;
  out.depthMm = depthMm;
  out.after = bone;
  out.approachMm = engine.advanceToContactMm(bone, revision, start, reachMm);
  if (out.approachMm) {
    Pose from = start;
    for (const Pose& pose : reamToDepthPoses(start, *out.approachMm, depthMm, stepMm)) {
      stopAsked();  // also where a step would make no Boolean
      const ReamComputation step = engine.compute(out.after, revision, pose, norm(pose.tip - from.tip), &from, control);
      ++out.steps;
      if (step.cut.changed && step.next) {
        out.after = *step.next;
        engine.adopt(++revision);
        ++out.cuts;
      }
      from = pose;
      out.lastPose = pose;
    }
  }
  out.removedMm3 = bone.volume() - out.after.volume();
  out.facesAfter = out.after.liveTriangleCount();
  return out;
}

void previewSeat(RemovalPreview& preview, const ReamerSpec& spec) {
  if (!preview.lastPose || !spec.meshFile.empty()) return;
  preview.seat = measureReamedSurface(preview.after.toMesh(), spec, *preview.lastPose);
}

}  // namespace reamsim
