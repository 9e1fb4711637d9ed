#pragma once
// A bone's undo history on disk, for crash recovery: one record per history state, appended as the bone is
// cut, so that a restore brings back every state (and the undo and redo between them), not only the last.
//
// A record holds what changed from the state before it in the history, in that history's own slot numbers
// (BoneState): the triangle slots removed, the vertices that are new (slot and exact coordinates) and the
// triangles added (slot and corner slots). The first state's record is the whole surface. Reading replays the
// records with BoneState::applyDelta and keeps a map from the written slots to the restored ones, so the
// restored states need not have the written slot numbers, and they share storage as the written ones did.
//
// The file only grows while its bone is cut: a record is never rewritten, an abandoned redo branch stays in it,
// and each record names the state it follows (its parent revision), so the chain the reader is asked for is
// found whatever else the file holds. Each record carries a checksum, and a record torn by a crash can only be
// the last one: nothing that names it (recovery.json is written after the append) was committed.
#include <cstdint>
#include <string>
#include <vector>

#include "reamsim/core/BoneHistory.h"

namespace reamsim {

class HistoryJournalWriter {
 public:
  // Opens (creating) the journal at `path`; the records already in it, up to the first incomplete one, count
  // as written. Revisions are unique within a process only (BoneHistory), so a journal must not be reopened
  // by another process: the recovery copy names each window's journals with a random token of its own.
  // Throws InputError naming the file when it cannot be opened.
  explicit HistoryJournalWriter(std::string path);

  // Appends a record for each entry of `entries` whose revision is not written yet (entries in history order,
  // the first one the history's first state). Throws InputError naming the file when it cannot be written;
  // the file is then cut back to its complete records.
  void append(const std::vector<BoneHistory::Entry>& entries);

  const std::string& path() const { return path_; }
  std::uint64_t bytes() const { return bytes_; }

 private:
  std::string path_;
  std::uint64_t bytes_ = 0;              // length of the complete records
  std::vector<std::uint64_t> written_;   // their revisions, sorted
};

// The history whose states are the records of `revisions` (the first state's first; each record must follow
// the one before it), with the cursor at `cursor`. Labels come from the records; revisions are new (this
// process's counter). Throws InputError naming the file and the problem: not a journal, a revision missing or
// following another state, a record that does not apply (a slot out of range, a vertex that is not there) or
// does not give the state's recorded triangle and vertex counts.
BoneHistory readHistoryJournal(const std::string& path, const std::vector<std::uint64_t>& revisions, std::size_t cursor);

// The revisions of the journal's complete records, in the order they were written: the whole history of a
// journal written at once for one history (a save's), to hand to readHistoryJournal. Throws InputError naming
// the file when it cannot be read or is not a journal.
std::vector<std::uint64_t> journalRevisions(const std::string& path);

}  // namespace reamsim
