#pragma once
// A bone's undo history saved beside it (NAME.ply.history.rsj, since session 57), so that a reopened bone undoes
// and redoes its cuts as before the save. The file is a history journal (reamsim/core/HistoryJournal.h) written
// whole for the one history; the bone file records its states and which of them the bone is (BoneFileFacts),
// to tell it from another save's.
#include <QString>
#include <cstdint>
#include <vector>

#include "reamsim/core/BoneHistory.h"
#include "reamsim/ui/BoneFileFacts.h"

namespace reamsim::ui {

QString historyPathBeside(const QString& bonePath);  // NAME.ply.history.rsj beside NAME.ply

// Writes every state of `history` (the redo ones too) to `path`: into a new file beside it, renamed over it when
// complete, so a failed write leaves what was there. Throws InputError naming the file.
void writeSavedHistory(const QString& path, const BoneHistory& history);

// The history a save wrote at `path` for a bone file whose facts are `saved` (historyStates set), at its last
// state (an undo stack built over it is then moved back to saved.historyCursor), with the revisions it was
// written under (the saved cut log's bone_state), state by state. Throws std::runtime_error naming the file and
// the problem: missing, not a journal, another number of states than recorded (another save's, or damaged), or a
// state at the save that is not `opened`, the bone as read from its file.
struct SavedHistoryRead {
  BoneHistory history;
  std::vector<std::uint64_t> writtenRevisions;
};
SavedHistoryRead readSavedHistory(const QString& path, const BoneFileFacts& saved, const BoneState& opened);

}  // namespace reamsim::ui
