#pragma once
// One edit of the note on a cut log row on the undo stack (the log dock's Note… or a double-click), so that
// Ctrl+Z takes back a note overwritten by mistake as it takes back a cut or a landmark edit. ReamSession
// records the edits as they reach the document (ReamSession::recordNoteEdits); a plan's note that comes with
// its step is part of the step, not an edit.
#include <QUndoCommand>
#include <cstddef>
#include <string>

#include "reamsim/core/NodeId.h"

namespace reamsim::ui {

class ReamSession;

class NoteCommand : public QUndoCommand {
 public:
  NoteCommand(ReamSession& session, NodeId log, std::size_t row, std::size_t stepIndex, std::string before,
              std::string after);
  void undo() override;
  void redo() override;  // the first redo is the edit itself, already in the document

 private:
  ReamSession& session_;
  NodeId log_;
  std::size_t row_;
  std::string before_, after_;
  bool first_ = true;
};

}  // namespace reamsim::ui
