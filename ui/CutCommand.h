#pragma once
// One committed cut on the undo stack. It holds no mesh: the states live in the bone's BoneHistory,
// which shares storage between states, so N cuts do not cost N meshes.
#include <QUndoCommand>

#include "reamsim/core/BoneNode.h"
#include "reamsim/core/CutLogEntry.h"

namespace reamsim::ui {

class CutCommand : public QUndoCommand {
 public:
  CutCommand(BoneNode& bone, const CutLogEntry& entry);
  // A step of the bone's history already committed elsewhere (the cuts before a crash, restored as one state).
  CutCommand(BoneNode& bone, const QString& text);
  void undo() override;
  void redo() override;  // the first redo is the cut itself, already committed by the session

 private:
  BoneNode& bone_;
  bool first_ = true;
};

}  // namespace reamsim::ui
