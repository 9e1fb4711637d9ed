#pragma once
// One edit of the cut bone's landmarks or planned axis on the undo stack (a landmark placed by a click, a
// landmarks file opened in the Planning dock, Aim, Clear the plan, the side), so that Ctrl+Z takes back the
// last edit, whether it was a cut or a landmark. ReamSession records the edits as they reach the document
// (ReamSession::recordPlanningEdit); a bone's landmarks that come with it (opened beside it, restored, an
// exchange) are not edits.
#include <QUndoCommand>

#include "reamsim/ream/ScapularFrame.h"

namespace reamsim::ui {

class ReamSession;

class PlanningCommand : public QUndoCommand {
 public:
  PlanningCommand(ReamSession& session, BonePlanning before, BonePlanning after);
  void undo() override;
  void redo() override;  // the first redo is the edit itself, already in the document

  // What changed, in words: "Place the glenoid centre", "Plan the axis", "Set the side: left", ...
  static QString describe(const BonePlanning& before, const BonePlanning& after);

 private:
  ReamSession& session_;
  BonePlanning before_, after_;
  bool first_ = true;
};

}  // namespace reamsim::ui
