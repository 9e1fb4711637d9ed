#include "CutCommand.h"

#include <QCoreApplication>

namespace reamsim::ui {

CutCommand::CutCommand(BoneNode& bone, const CutLogEntry& entry) : bone_(bone) {
  setText(QCoreApplication::translate("CutCommand", "Cut %1: %L2 mm³, %L3 faces")
              .arg(entry.stepIndex)
              .arg(entry.removedMm3, 0, 'f', 2)
              .arg(entry.faces));
}

CutCommand::CutCommand(BoneNode& bone, const QString& text) : bone_(bone) { setText(text); }

void CutCommand::undo() { bone_.undo(); }

void CutCommand::redo() {
  if (first_) {
    first_ = false;
    return;
  }
  bone_.redo();
}

}  // namespace reamsim::ui
