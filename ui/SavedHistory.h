#pragma once
// A bone's undo history saved beside it (NAME.ply.history.rsj, since session 57), so that a reopened bone undoes
// and redoes its cuts as before the save. The file is a history journal (reamsim/core/HistoryJournal.h) written
// whole for the one history; the bone file records its states and which of them the bone is (BoneFileFacts),
// to tell it from another save's.
#include <QString>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "reamsim/core/BoneHistory.h"
#include "reamsim/ui/BoneFileFacts.h"

class QUndoStack;

namespace reamsim::ui {

QString historyPathBeside(const QString& bonePath);  // NAME.ply.history.rsj beside NAME.ply

// Whether a save to `bonePath` can take its undo history: the state at the save must read back exactly, and a
// binary STL (what the mesh import plugin writes for .stl) stores single-precision coordinates.
bool keepsExactCoordinates(const QString& bonePath);

// The states of `history` a reopened bone should get back: all up to its cursor, and of those after it the ones
// the undo stack can still redo (a CutCommand each, directly above the stack's index, before any command that
// changes which bone is cut). The history keeps redo states the stack dropped when another edit was pushed.
std::vector<BoneHistory::Entry> statesToSave(const BoneHistory& history, const QUndoStack& stack);

// Writes `states` (a history's, the first its first state) as a journal in a new file beside `path`
// (PATH.partial), returned; commitSavedHistory renames it over `path` once the bone file `bonePath` is written,
// and discardSavedHistory removes it when the save stops. The new file takes the owner, group, mode and ACLs of
// the history it replaces, or else of the bone file (keepFileAttributes). Throws InputError naming the file.
QString writeSavedHistoryPart(const QString& path, const std::vector<BoneHistory::Entry>& states, const QString& bonePath);
void commitSavedHistory(const QString& part, const QString& path, const QString& bonePath);
void discardSavedHistory(const QString& part);

// The history a save wrote at `path` for a bone file whose facts are `saved` (historyStates set), at its last
// state (an undo stack built over it is then moved back to saved.historyCursor), with the revisions it was
// written under (the saved cut log's bone_state), state by state. Throws std::runtime_error naming the file and
// the problem: missing, not a journal, another number of states than recorded (another save's, or damaged), or a
// state at the save that is not `opened`, the bone as read from its file.
struct SavedHistoryRead {
  BoneHistory history;
  std::vector<std::uint64_t> writtenRevisions;
};
// What readSavedHistory throws when the history reads back whole but its state at the save is another bone.
class SavedHistoryAtAnotherBone : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// Checks that `state` (a history's, read back from a journal) is `bone` (as read from the bone file beside it):
// the same faces and volume (to 1e-9). Throws SavedHistoryAtAnotherBone, `problem` followed by both counts. A
// save's history and a crash copy's are both checked so.
void requireStateIsBone(const BoneState& state, const BoneState& bone, const std::string& problem);
SavedHistoryRead readSavedHistory(const QString& path, const BoneFileFacts& saved, const BoneState& opened);

}  // namespace reamsim::ui
