// MainWindow: crash recovery — a copy of the unsaved bone and its cut log on disk, written off the UI thread
// a moment after each change, removed by a save or a normal close, offered at the next start after a crash
// (RecoveryFiles.h; docs/GUI.md "Unsaved changes").
#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
#include <QFutureWatcher>
#include <QtConcurrent/QtConcurrentRun>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "BoneCommands.h"
#include "BonePlacement.h"
#include "CutCommand.h"
#include "OtherBonesLayer.h"
#include "MainWindow.h"
#include "PluginHost.h"
#include "RecoveryFiles.h"
#include "RecoveryRead.h"
#include "WriteProgressDialog.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/tools/ReamerFile.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::ui {

void MainWindow::enableRecovery(const QString& dir, int delayMs) {
  if (recovery_) return;
  recovery_ = std::make_unique<RecoveryFiles>(dir);
  if (!recovery_->owns()) {  // another ReamSim window keeps its copy there
    recovery_.reset();
    return;
  }
  recoveryTimer_.setSingleShot(true);
  recoveryTimer_.setInterval(delayMs);
  connect(&recoveryTimer_, &QTimer::timeout, this, &MainWindow::writeRecoveryCopy);
  // At most one copy per delay while the user keeps cutting (restarting the timer on every change would
  // write none during a long feed).
  const auto schedule = [this] {
    if (!recoveryOfferPending_ && !recoveryTimer_.isActive()) recoveryTimer_.start();
  };
  connect(session_->undoStack(), &QUndoStack::indexChanged, this, schedule);
  connect(session_->undoStack(), &QUndoStack::cleanChanged, this, schedule);
  // Landmarks placed on a bone with unsaved cuts are the user's work too: the copy follows them.
  landmarksSubscription_ = session_->document().observeNode(session_->bone()->id(), [this, schedule] {
    if (!copiedPlanning_ || planningOf(*session_->bone()) != *copiedPlanning_) schedule();
  });
  // So are the notes written on the log's rows.
  recoveryNotesSubscription_ = session_->document().subscribe([this, schedule](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Log && copiedNotesRevision_ != session_->log()->notesRevision()) schedule();
  });
  connect(&recoveryWrite_, &QFutureWatcher<RecoveryWrite>::finished, this, [this] {
    const RecoveryWrite result = recoveryWrite_.result();
    if (result.error.isEmpty()) return;
    if (result.written) {  // the bone, its log and landmarks are in it; only the undo steps are not
      statusBar()->showMessage(tr("Crash-recovery copy written without its undo history: %1").arg(result.error), 10000);
      return;
    }
    copiedPlanning_.reset();
    copiedNotesRevision_.reset();  // not in a copy: the next change of the planning writes one again
    statusBar()->showMessage(tr("No crash-recovery copy: %1").arg(result.error), 10000);
  });
  if (recovery_->found()) {
    recoveryOfferPending_ = true;
    QTimer::singleShot(0, this, &MainWindow::offerRecovery);
  } else if (hasUnsavedChanges()) {
    schedule();
  }
}

void MainWindow::writeRecoveryCopy() {
  if (!recovery_ || recoveryOfferPending_) return;
  if (recoveryWrite_.isRunning()) {  // the next copy once this one is written
    recoveryTimer_.start();
    return;
  }
  // The snapshot on the UI thread (the document's thread; a bone state is an immutable value, cheap to
  // copy), the mesh and the files on a worker. The other bones whose cuts no save wrote go too, to be restored
  // beside the cut bone: Save writes the cut bone only. They are the bones beside and the bones a CT import
  // replaced (held by the undo history, which a restore does not bring back).
  struct BesideCopy {
    BoneState state;
    PatientFrame frame;
  };
  std::vector<BesideCopy> besideCopies;
  CopyDescription description;
  for (const BoneNode* b : unsavedBonesBeside()) {
    besideCopies.push_back({b->current(), b->patientFrame()});
    description.besideNames << QString::fromStdString(b->name());
  }
  for (const BoneContent* replaced : unsavedReplacedBones()) {
    besideCopies.push_back({replaced->history.current(), replaced->patientFrame});
    description.besideNames << tr("%1 (replaced by a CT import)").arg(QString::fromStdString(replaced->name));
  }
  if (!hasUnsavedChanges() && besideCopies.empty()) {
    removeRecoveryCopy();
    return;
  }
  const MeshImportInterface* writer = plugins_.meshImport();
  if (!writer) return;  // nothing here writes meshes
  BoneState state = session_->bone()->current();
  // The undo history goes into its journal (HistoryJournal.h): each state once, appended, so a copy costs the
  // cuts since the last one, not the whole history.
  const BoneHistory& history = session_->bone()->history();
  std::vector<BoneHistory::Entry> entries = history.entries();  // states share storage: cheap to copy
  description.history.emplace();
  for (const BoneHistory::Entry& e : entries) description.history->revisions.push_back(e.revision);
  description.history->cursor = history.cursor();
  std::string csv = cutLogCsv(withUndoneMarked(session_->log()->entries(), session_->bone()->history()));
  copiedNotesRevision_ = session_->log()->notesRevision();
  const PatientFrame frame = session_->bone()->patientFrame();
  description.name = boneName_;
  copiedPlanning_ = planningOf(*session_->bone());
  if (*copiedPlanning_ != BonePlanning{})
    description.landmarksJson = QString::fromStdString(planningToJson(*copiedPlanning_, "crash-recovery copy"));
  description.cuts = static_cast<int>(session_->log()->entries().size());
  description.removedMm3 = session_->initialVolumeMm3() - state.volume();  // undone cuts not counted
  const ReamerSpec& reamer = session_->reamer()->spec();
  if (reamer.meshFile.empty())
    description.reamerPreset = QString::fromStdString(reamer.name);
  else
    description.reamerMesh = QString::fromStdString(reamer.meshFile);
  const RecoveryFiles* files = recovery_.get();
  std::unique_ptr<HistoryJournalWriter>* journal = &journal_;  // the worker's alone while it runs
  recoveryWrite_.setFuture(QtConcurrent::run(
      [writer, files, frame, state = std::move(state), csv = std::move(csv), besideCopies = std::move(besideCopies),
       journal, entries = std::move(entries), description = std::move(description)]() mutable -> RecoveryWrite {
        // Without its history the copy still holds the bone: a journal that cannot be written is reported, not
        // a reason to keep no copy.
        QString historyError;
        try {
          const std::string path = files->historyPath(description.history->revisions.front()).toStdString();
          if (!*journal || (*journal)->path() != path) *journal = std::make_unique<HistoryJournalWriter>(path);
          (*journal)->append(entries);
        } catch (const std::exception& e) {
          journal->reset();  // commit removes its file: the next copy starts it again
          description.history.reset();
          historyError = QString::fromStdString(e.what());
        }
        QString error;
        try {
          writer->exportMesh(state.toMesh(), files->nextBonePath().toStdString(), BoneFileFacts::ofFrame(frame));
          writeTextFile(files->nextLogPath().toStdString(), csv);
          for (std::size_t i = 0; i < besideCopies.size(); ++i)
            writer->exportMesh(besideCopies[i].state.toMesh(), files->nextBesidePath(int(i)).toStdString(),
                               BoneFileFacts::ofFrame(besideCopies[i].frame));
        } catch (const std::exception& e) {
          return RecoveryWrite{QString::fromStdString(e.what()), false};
        }
        files->commit(description, error);
        if (!error.isEmpty()) return RecoveryWrite{error, false};
        if (!historyError.isEmpty())
          return RecoveryWrite{QObject::tr("the undo history is not in the copy (%1)").arg(historyError), true};
        return RecoveryWrite{{}, true};
      }));
}

void MainWindow::endRecovery() {
  if (!recovery_) return;
  recoveryTimer_.stop();
  if (recoveryWrite_.isRunning()) recoveryWrite_.waitForFinished();
  if (!recoveryOfferPending_) removeRecoveryCopy();
}

// Only while no copy is being written (the worker uses the journal's writer).
void MainWindow::removeRecoveryCopy() {
  recovery_->remove();
  journal_.reset();
  copiedPlanning_.reset();  // no copy: any planning differs from it
}

void MainWindow::offerRecovery() {
  const std::optional<RecoveredBone> found = recovery_ ? recovery_->found() : std::nullopt;
  if (!found) {
    recoveryOfferPending_ = false;
    return;
  }
  const QString name = found->name.isEmpty() ? tr("the bone") : found->name;
  QMessageBox box(QMessageBox::Question, tr("Recover unsaved work"),
                  tr("ReamSim did not close normally last time. A copy of %1 with %2 cuts, written %3, was kept.")
                      .arg(name)
                      .arg(found->cuts)
                      .arg(QLocale().toString(found->written, QLocale::ShortFormat)),
                  QMessageBox::NoButton, this);
  box.setObjectName("RecoveryDialog");
  const QString besideText =
      found->beside.empty() ? QString()
      : found->beside.size() == 1 ? tr(" Another bone with unsaved cuts, %1, is restored beside it.").arg(found->beside.front().name)
                                  : tr(" %1 other bones with unsaved cuts are restored beside it.").arg(found->beside.size());
  box.setInformativeText(tr("Restore it in place of the bone now open?%1 Discard deletes the copy.").arg(besideText));
  QPushButton* restore = box.addButton(tr("Restore"), QMessageBox::AcceptRole);
  box.addButton(QMessageBox::Discard);
  box.setDefaultButton(restore);
  box.exec();
  if (box.clickedButton() != restore) {
    recoveryOfferPending_ = false;
    removeRecoveryCopy();
    if (hasUnsavedChanges()) recoveryTimer_.start();
    return;
  }
  // Read on a worker behind a progress dialog with Cancel; meanwhile the copy is neither written nor removed
  // (recoveryOfferPending_ holds).
  std::optional<RecoveredRead> read;
  QString problem;
  try {
    if (!plugins_.meshImport()) throw std::runtime_error("no mesh import plugin is loaded (Help → Plugins)");
    if (!session_->reamer()->cuttingVolume()) session_->setReamer(loadPreset(kDefaultReamerPreset, reamerPresetsPath()));
    read = readRecoveryCopyInteractive(*found);
    if (!read->error.empty()) problem = QString::fromStdString(read->error);
  } catch (const std::exception& e) {
    problem = QString::fromStdString(e.what());
  }
  recoveryOfferPending_ = false;
  if (read && read->cancelled) {
    // Kept for the next start; this window stops managing the folder, so that no copy of its own replaces it.
    statusBar()->showMessage(tr("Restore cancelled: the copy is kept in %1 and offered again at the next start")
                                 .arg(recovery_->dir()), 15000);
    recovery_.reset();
    return;
  }
  if (!problem.isEmpty()) {
    // The copy stays where it is for the user to open by hand; this window stops managing the folder.
    showError(tr("Cannot restore the recovered bone"), tr("%1\n\nThe copy is kept in %2.").arg(problem, recovery_->dir()));
    recovery_.reset();
    return;
  }
  ImportedBone bone = std::move(read->bone);
  const BoneState copied = BoneState::fromMesh(bone.mesh);
  session_->plan()->setPoses({});
  installBone(std::move(bone), tr("%1 (recovered)").arg(name), {});
  restoreRecoveredReamer(*found);
  restoreRecoveredLandmarks(*found);
  // The undo history up to the crash, from its journal, with the History dock's steps: undo and redo as before
  // the crash. One that cannot be read back (or does not end at the copied bone) is reported and kept; the
  // recovered bone is then the history's only state.
  std::unordered_map<std::uint64_t, std::uint64_t> revisionMap;  // the crashed history's revisions → the adopted ones
  if (!read->historyError.empty()) {
    const QString kept = keepInRestored(found->historyPath);
    showError(tr("The undo history was not restored"),
              tr("The recovered bone is restored, but not its undo history (Undo cannot go back before it):\n%1\n\n"
                 "The history is kept as %2.").arg(QString::fromStdString(read->historyError), kept));
  }
  if (read->history) {
    session_->adoptHistory(std::move(*read->history));
    const BoneHistory& adopted = session_->bone()->history();
    for (std::size_t k = 0; k < adopted.size() && k < found->historyRevisions.size(); ++k)
      revisionMap[found->historyRevisions[k]] = adopted.entries()[k].revision;
    stackAdoptedSteps(tr("before the crash"));
    session_->undoStack()->setIndex(int(found->historyCursor));  // undoes what had been undone before the crash
  }
  session_->restartPath(ReamSession::PathStart::AsRecovered);  // the recovered bone is where a path starts
  // Both on the history's own volume origin (the copied mesh's volume may differ by rounding).
  const double originalVolume = session_->bone()->history().entries().front().state.volume();
  const double atCopyVolume = session_->bone()->current().volume();
  recoveredRevisions_.insert(session_->bone()->history().entries().front().revision);  // also once moved beside
  session_->moveReamer(startPoseFor(copied.bounds()));
  restoreBonesBeside(*found, read->beside);
  session_->undoStack()->resetClean();  // saved nowhere but in the recovery copy
  savedBoneRevision_.reset();
  // The log up to the crash goes back into the log panel. One that cannot be read is kept as a file for
  // the user (named in the message), never dropped.
  std::size_t logRows = 0;
  if (!found->logPath.isEmpty()) {
    try {
      std::vector<CutLogEntry> rows = readCutLogCsv(found->logPath.toStdString());
      logRows = rows.size();
      // What was removed before the history's first state: all of it when that is the recovered bone, less the
      // cuts between the two when it is the bone as opened.
      const double removed = found->removedMm3.value_or(rows.empty() ? 0.0 : rows.back().cumulativeMm3);
      session_->continueLog(std::move(rows), removed - (originalVolume - atCopyVolume), revisionMap);
    } catch (const std::exception& e) {
      recoveredLogPath_ = keepInRestored(found->logPath);
      showError(tr("The cut log was not restored"),
                tr("%1 was restored, but its cut log could not be read back:\n%2\n\nThe log is kept as %3.")
                    .arg(name, QString::fromStdString(e.what()), recoveredLogPath_));
      return;
    }
  }
  const QString steps = logRows == 1 ? tr("1 step") : tr("%1 steps").arg(logRows);
  const int undoSteps = session_->undoStack()->count();
  statusBar()->showMessage(undoSteps > 0 ? tr("Restored %1, its cut log (%2) and its undo history (%3 steps)").arg(name, steps).arg(undoSteps)
                                         : tr("Restored %1 and its cut log (%2)").arg(name, steps),
                           20000);
}

// The reamer the crashed session cut with. One that cannot be had any more (a preset renamed, a mesh file gone)
// is named in a message; the window's reamer stays.
// Landmarks that cannot be read back are named in the status bar: the bone is what matters here.
void MainWindow::restoreRecoveredLandmarks(const RecoveredBone& found) {
  if (found.landmarksJson.isEmpty()) return;  // none placed, or a copy from before session 54
  try {
    const ReamSession::QuietPlanning quiet(*session_);  // restored with the bone: not an edit to undo
    applyPlanning(*session_->bone(), parsePlanningJson(found.landmarksJson.toStdString(),
                                                        recovery_->dir().toStdString() + "/recovery.json"));
  } catch (const std::exception& e) {
    statusBar()->showMessage(tr("The landmarks of the copy could not be read: %1").arg(e.what()), 15000);
  }
}

void MainWindow::restoreRecoveredReamer(const RecoveredBone& found) {
  if (found.reamerPreset.isEmpty() && found.reamerMesh.isEmpty()) return;  // a copy from before session 53
  const QString reamer = found.reamerMesh.isEmpty() ? found.reamerPreset : found.reamerMesh;
  try {
    const ReamerSpec spec = found.reamerMesh.isEmpty() ? loadPreset(found.reamerPreset.toStdString(), reamerPresetsPath())
                                                       : meshReamerSpec(found.reamerMesh.toStdString());
    const ReamerSpec& now = session_->reamer()->spec();
    if (spec.name == now.name && spec.meshFile == now.meshFile) return;
    session_->setReamer(spec);
    session_->plan()->setReamerSpecName(spec.name);
  } catch (const std::exception& e) {
    showError(tr("The reamer was not restored"),
              tr("The crashed session cut with %1, which cannot be used now:\n%2\n\nThe reamer stays %3.")
                  .arg(reamer, QString::fromStdString(e.what()), QString::fromStdString(session_->reamer()->spec().name)));
  }
}

// readRecoveryCopy on a worker, behind a window-modal dialog that shows the stage and has Cancel; the window keeps
// painting meanwhile (a local event loop, as a save's).
RecoveredRead MainWindow::readRecoveryCopyInteractive(const RecoveredBone& copy) {
  WriteProgressDialog dialog(tr("Restoring %1").arg(copy.name.isEmpty() ? tr("the bone") : copy.name), this, tr("Restoring"));
  const MeshImportInterface* importer = plugins_.meshImport();
  return dialog.runWhileShown(
      [importer, copy](const ProgressCallback& progress) { return readRecoveryCopy(*importer, copy, progress); });
}

// A copy of `file` where the next save or close does not remove it (recovery/restored/), for a file that could
// not be read back.
QString MainWindow::keepInRestored(const QString& file) const {
  const QString kept = QDir(recovery_->dir()).filePath("restored");
  QDir().mkpath(kept);
  const QString keptFile =
      QDir(kept).filePath(QDateTime::currentDateTime().toString("yyyyMMdd-HHmmss") + "_" + QFileInfo(file).fileName());
  QFile::copy(file, keptFile);
  return keptFile;
}

// The bones beside of a recovery copy, beside the restored bone (not undoable: like the restore itself, the
// start of this window's history). They count as unsaved until a save writes them (unsavedBonesBeside). One
// that cannot be read is named in a message; the others are restored.
void MainWindow::restoreBonesBeside(const RecoveredBone& found, std::vector<RecoveredRead::Beside>& bones) {
  QStringList failed;
  for (std::size_t i = 0; i < found.beside.size() && i < bones.size(); ++i) {
    const RecoveredBone::Beside& copy = found.beside[i];
    try {
      if (!bones[i].bone) throw std::runtime_error(bones[i].error);
      ImportedBone read = std::move(*bones[i].bone);
      read.source = tr("crash-recovery copy of %1").arg(copy.name).toStdString();
      BoneContent content = boneContentFrom(std::move(read), tr("%1 (recovered)").arg(copy.name).toStdString(), "recovered");
      recoveredRevisions_.insert(content.history.entries().front().revision);
      auto node = std::make_unique<BoneNode>(content.name);
      node->swapContent(content);
      session_->document().add(std::move(node));
    } catch (const std::exception& e) {
      failed << tr("%1 (kept as %2)").arg(QString::fromStdString(e.what()), keepInRestored(copy.path));
    }
  }
  if (!failed.isEmpty()) showError(tr("A bone beside was not restored"), failed.join("\n"));
  if (!found.beside.empty()) otherBones_->fitViewToAll();
}

}  // namespace reamsim::ui
