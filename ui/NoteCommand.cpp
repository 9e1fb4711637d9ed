#include "NoteCommand.h"

#include <QCoreApplication>
#include <utility>

#include "ReamSession.h"

namespace reamsim::ui {

NoteCommand::NoteCommand(ReamSession& session, NodeId log, std::size_t row, std::size_t stepIndex, std::string before,
                         std::string after)
    : session_(session), log_(log), row_(row), before_(std::move(before)), after_(std::move(after)) {
  const auto tr = [](const char* text) { return QCoreApplication::translate("NoteCommand", text); };
  setText((after_.empty() ? tr("Clear the note on step %1") : tr("Note on step %1")).arg(stepIndex));
}

void NoteCommand::undo() { session_.restoreNote(log_, row_, before_, after_); }

void NoteCommand::redo() {
  if (std::exchange(first_, false)) return;
  session_.restoreNote(log_, row_, after_, before_);
}

}  // namespace reamsim::ui
