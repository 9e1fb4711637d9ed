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
#include <functional>
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
  // The bone as it was opened (its history's first state), when cuts were on top of it (session 53): the
  // restore puts it under the recovered bone, so that undo goes back to it. Empty without one.
  QString originalPath;
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
  // The bone as it was opened, under a name of its own (its revision): written once however many copies
  // follow, since it does not change while the bone is cut. Written whole or not at all (`writeOriginal`
  // gets a temporary path, then it is renamed), so one that exists is complete.
  QString originalPath(std::uint64_t revision) const;  // "original-<revision>.ply"
  // False with `error` when it cannot be written; nothing is left under the final name then.
  bool writeOriginal(std::uint64_t revision, const std::function<void(const QString& path)>& write, QString& error) const;
  // False (with `error` naming the file) when the description cannot be written; the previous copy stays.
  // `besideNames`: the bones beside written to nextBesidePath(0…), in order. `originalRevision`: the
  // original written by writeOriginal, 0 for none; the other originals are removed once the description
  // names it.
  bool commit(const QString& name, int cuts, double removedMm3, const QStringList& besideNames,
              std::uint64_t originalRevision, QString& error) const;
  void remove() const;  // the description first, so a half-removed copy is never offered

 private:
  QString path(const QString& file) const;
  QString besidePath(const QString& slot, int index) const;
  QString currentSlot() const;  // "a", "b", or "" without a description
  QString nextSlot() const { return currentSlot() == "a" ? "b" : "a"; }
  QString dir_;
  std::unique_ptr<QLockFile> lock_;
};

}  // namespace reamsim::ui
