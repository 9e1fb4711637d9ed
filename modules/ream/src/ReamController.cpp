#include "reamsim/ream/ReamController.h"

#include <chrono>

namespace reamsim {

ReamController::ReamController(Document& document, BoneNode& bone, ReamerNode& reamer, LogNode& log,
                               AlertNode* alerts, CutBackendFactory cut,
                               std::unique_ptr<ContactBackend> contact)
    : document_(document),
      bone_(bone),
      reamer_(reamer),
      log_(log),
      alerts_(alerts),
      engine_(reamer.cuttingVolume(), std::move(contact), std::move(cut), reamer.spec()) {
  engine_.prepare(bone_.current(), bone_.currentRevision());
}

ReamController::~ReamController() = default;

ReamStepOutcome ReamController::moveTo(const Pose& pose, bool placed, const std::string& note) {
  // A plan is a path: each step moves from the previous pose, and a sideways move cuts what it sweeps.
  if (placed) previous_.reset();
  const double stepMm = previous_ ? norm(pose.tip - previous_->tip) : 0.0;
  ReamComputation c =
      engine_.compute(bone_.current(), bone_.currentRevision(), pose, stepMm, previous_ ? &*previous_ : nullptr);
  previous_ = pose;
  ReamStepOutcome out;
  out.contact = c.contact;
  out.cut = c.cut;
  out.volumeBookkeepingError = c.volumeBookkeepingError;
  out.swept = c.swept;
  out.sweepCuts = c.sweepCuts;
  out.times = c.times;
  const auto commitStart = std::chrono::steady_clock::now();
  CommitOptions options;
  options.note = note;
  out.entry = commitReamStep(document_, bone_, reamer_, log_, alerts_, c, steps_++, options);
  if (out.entry.boneStateId != 0) engine_.adopt(out.entry.boneStateId);
  out.commitMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - commitStart).count();
  return out;
}

BoneInvariants ReamController::checkBone() const { return engine_.checkBone(); }

}  // namespace reamsim
