#pragma once
// Crash recovery on disk: while the bone has unsaved changes, a copy of it (PLY, with its patient frame) and
// of its cut log (CSV) is kept in one folder with a short description (recovery.json). A normal close or a
// save removes it; a copy found when a window starts means the last session ended without either (a crash,
// a kill, a power cut), and the window offers to restore it. One window at a time owns the folder
// (QLockFile, freed when its process dies): a second ReamSim running beside it keeps no copy.
//
// Files only; when and what to write is MainWindow's (MainWindowRecovery.cpp).
#include <QDateTime>
#include <QString>
#include <QStringList>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

class QLockFile;

namespace reamsim::ui {

struct RecoveredBone {
  QString bonePath, logPath;
  QString name;       // the bone's name as the window's title showed it
  QDateTime written;  // when the copy was complete
  int cuts = 0;
  // The bone volume removed since its log began, at the copy (the log's last row counts cuts undone since;
  // this does not). Unset in a description written before session 49.
  std::optional<double> removedMm3;
  // Bones beside the cut bone whose cuts no save wrote (session 52): restored beside it.
  struct Beside {
    QString name, path;
  };
  std::vector<Beside> beside;
  // The bone's undo history (session 53): the journal (HistoryJournal.h) and, in it, the revisions of the
  // history's states in order and the position among them of the copied bone. Empty without one.
  QString historyPath;
  std::vector<std::uint64_t> historyRevisions;
  std::size_t historyCursor = 0;
  QString reamerPreset, reamerMesh;  // the reamer cut with (empty in a copy written before session 53)
  QString landmarksJson;  // the bone's scapular landmarks as a landmark file's text (empty: none placed)
};

// The history a copy names: its journal is RecoveryFiles::historyPath(revisions.front()).
struct HistoryInCopy {
  std::vector<std::uint64_t> revisions;
  std::size_t cursor = 0;
};

// What a copy's description (recovery.json) says besides its files' slot.
struct CopyDescription {
  QString name;  // the bone's name as the window's title shows it
  int cuts = 0;
  double removedMm3 = 0;
  QStringList besideNames;               // the bones written to nextBesidePath(0…), in order
  std::optional<HistoryInCopy> history;  // what of the journal belongs to this copy (none: the bone alone)
  QString reamerPreset, reamerMesh;      // the reamer cut with: a preset's name, or a mesh file (session 53)
  QString landmarksJson;                 // the bone's landmarks (a landmark file's text; empty: none placed)
};

class RecoveryFiles {
 public:
  explicit RecoveryFiles(const QString& dir);  // creates the folder and tries its lock
  ~RecoveryFiles();
  bool owns() const;  // this window holds the lock: it may write, offer and remove the copy
  const QString& dir() const { return dir_; }

  std::optional<RecoveredBone> found() const;  // a complete copy (description written last)

  // Writing a copy so that a crash at any point leaves a complete one (the previous or the new): two slots,
  // a and b; the new files go to the slot the description does not name, then commit() points the
  // description at it (written whole or not at all: QSaveFile). Safe on a worker thread (files only).
  QString nextBonePath() const;  // "bone.a.ply" or "bone.b.ply": the writer picks the format from the suffix
  QString nextLogPath() const;
  QString nextBesidePath(int index) const;  // "beside<index>.a.ply" or ".b.ply": a bone beside
  // The journal of the undo history whose first state has `firstRevision`: one file per bone, appended to by
  // every copy (HistoryJournalWriter), never rewritten, so the copies' two slots do not apply to it. Named
  // with a random token of this object's as well: revisions restart in every process, and a journal left by
  // another one (the crashed session, or an earlier crash) must never be appended to.
  QString historyPath(std::uint64_t firstRevision) const;  // "history-<token>-<revision>.rsj"
  // False (with `error` naming the file) when the description cannot be written; the previous copy stays.
  // Once the description names its history, other bones' journals go.
  bool commit(const CopyDescription& copy, QString& error) const;
  void remove() const;  // the description first, so a half-removed copy is never offered

 private:
  QString path(const QString& file) const;
  QString besidePath(const QString& slot, int index) const;
  QString currentSlot() const;  // "a", "b", or "" without a description
  QString nextSlot() const { return currentSlot() == "a" ? "b" : "a"; }
  QString dir_;
  QString token_;  // random, for this object's journal names
  std::unique_ptr<QLockFile> lock_;
};

}  // namespace reamsim::ui
