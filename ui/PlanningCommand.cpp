#include "PlanningCommand.h"

#include <QCoreApplication>

#include "ReamSession.h"

namespace reamsim::ui {

PlanningCommand::PlanningCommand(ReamSession& session, BonePlanning before, BonePlanning after)
    : session_(session), before_(std::move(before)), after_(std::move(after)) {
  setText(describe(before_, after_));
}

void PlanningCommand::undo() { session_.restorePlanning(before_, after_); }

void PlanningCommand::redo() {
  if (std::exchange(first_, false)) return;
  session_.restorePlanning(after_, before_);
}

QString PlanningCommand::describe(const BonePlanning& before, const BonePlanning& after) {
  const auto tr = [](const char* text) { return QCoreApplication::translate("PlanningCommand", text); };
  int changed = 0;
  std::optional<ScapulaLandmark> which;
  for (ScapulaLandmark l : kScapulaLandmarks)
    if (before.landmarks[l] != after.landmarks[l]) {
      ++changed;
      which = l;
    }
  const bool sideChanged = before.landmarks.side != after.landmarks.side;
  const bool axisChanged = BonePlanning{{}, before.plannedAxis} != BonePlanning{{}, after.plannedAxis};
  if (changed == 1 && !axisChanged)
    return (after.landmarks[*which] ? tr("Place the %1") : tr("Remove the %1")).arg(displayName(*which));
  if (changed == 0 && sideChanged && !axisChanged)
    return tr("Set the side: %1").arg(toString(after.landmarks.side));
  if (changed == 0 && !sideChanged && axisChanged)
    return after.plannedAxis ? tr("Plan the axis") : tr("Clear the planned axis");
  return tr("Change the landmarks and the plan");
}

}  // namespace reamsim::ui
