// MainWindow: bones in and out — default case, open (off the UI thread), save, recent files, drag and drop,
// and the question before unsaved changes would be lost.
#include <QBuffer>
#include <QCoreApplication>
#include <QDateTime>
#include <QCloseEvent>
#include <QDragEnterEvent>
#include <QDir>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <QUndoStack>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_set>
#include <utility>

#include "BonePlacement.h"
#include "BoneCommands.h"
#include "CutCommand.h"
#include "MainWindow.h"
#include "PluginHost.h"
#include "WriteProgressDialog.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamReport.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/tools/ReamerPresets.h"
#include "reamsim/mesh/FileReplace.h"
#include "reamsim/ui/ProgressRelay.h"

namespace reamsim::ui {
namespace {

constexpr int kMaxRecent = 8;

}  // namespace

bool MainWindow::loadDefaultCase() {
  try {
    DefaultBone d = loadDefaultBone();
    const ReamPlan plan = loadPlan(defaultPlanPath());
    session_->setReamer(loadPreset(plan.reamer.empty() ? kDefaultReamerPreset : plan.reamer, reamerPresetsPath()));
    ImportedBone bone;
    bone.report = "bundled default scapula: " + d.meshPath;
    bone.original = std::make_shared<const TriangleMesh>(d.mesh);
    bone.mesh = std::move(d.mesh);
    bone.cuttable = true;  // the bundled bone is stored repaired (closed, outward, no self-intersections)
    bone.source = "bundled default scapula (OpenSim bone frame)";
    const std::vector<Pose> poses = plan.expandedPoses();
    const Pose start = plan.feed ? plan.feed->start : (poses.empty() ? startPoseFor(Bounds{}) : poses.front());
    session_->plan()->setReamerSpecName(plan.reamer);
    session_->plan()->setPoses(poses);
    session_->plan()->setFeedDescription(plan.description);
    installBone(std::move(bone), tr("default scapula"), {});
    try {  // the case runs without them: version and inclination wait for landmarks placed by hand
      const ReamSession::QuietPlanning quiet(*session_);  // they come with the bone: not an edit to undo
      session_->bone()->setLandmarks(loadDefaultLandmarks());
      savedPlanning_ = planningOf(*session_->bone());  // bundled: nothing to save
      updateTitle();
    } catch (const std::exception& e) {
      statusBar()->showMessage(tr("The default scapula's landmarks could not be read: %1").arg(e.what()), 15000);
    }
    session_->moveReamer(start);  // the user's path: the first collision query runs at the start pose
    view_->setStandardView(BoneView::StandardView::Anterior);
    return true;
  } catch (const std::exception& e) {
    showError(tr("Default case"), QString::fromStdString(e.what()));
    return false;
  }
}

void MainWindow::openFile(const QString& path, bool repair) {
  if (!plugins_.meshImport()) {
    showError(tr("Open"), tr("Cannot open %1: no mesh import plugin is loaded (Help → Plugins).").arg(path));
    return;
  }
  if (importWatcher_.isRunning()) {
    showError(tr("Open"), tr("Still importing %1.").arg(importPath_));
    return;
  }
  importPath_ = path;
  importCancelled_ = false;
  statusBar()->showMessage(tr("Importing %1…").arg(path));
  importBusy_->setRange(0, 0);  // busy until the reading reports a fraction
  importBusy_->setVisible(true);
  importCancel_->setVisible(true);
  const MeshImportInterface* importer = plugins_.meshImport();
  const std::string file = path.toStdString();
  importStop_ = std::make_shared<std::atomic<bool>>(false);
  const RepairProgress progress = progressRelay(
      this, [this](double fraction, const QString& stage) { showImportProgress(fraction, stage); }, importStop_);
  importWatcher_.setFuture(QtConcurrent::run([importer, file, repair, progress] {
    ImportOutcome out;
    try {
      out.bone = importer->importBone(file, repair, progress);
      if (out.bone.saved.historyStates) {
        // Read and replayed whole (~0.1 s at 405k faces): asked first whether to go on.
        if (progress && !progress(1.0, "undo history")) throw ReadCancelled("undo history");
        try {
          out.history = readSavedHistory(historyPathBeside(QString::fromStdString(file)), out.bone.saved,
                                         BoneState::fromMesh(out.bone.mesh));
        } catch (const SavedHistoryAtAnotherBone& e) {
          out.historyError = QString::fromStdString(e.what());
          // The repair on opening may have rebuilt what the save wrote.
          const TriangleMesh* read = out.bone.original.get();
          if (read && (read->vertices != out.bone.mesh.vertices || read->triangles != out.bone.mesh.triangles))
            out.historyError += QCoreApplication::translate(
                "MainWindow", " (the bone was repaired on opening: open it without repair, File → Open without repair, "
                              "to keep its undo history)");
        } catch (const std::exception& e) {
          out.historyError = QString::fromStdString(e.what());
        }
      }
    } catch (const StageCancelled& e) {  // reading, validating or repairing
      out.stoppedAt = QString::fromStdString(e.stage());
    } catch (const std::exception& e) {
      out.error = QString::fromStdString(e.what());
    }
    return out;
  }));
}

void MainWindow::showImportProgress(double fraction, const QString& stage) {
  if (!importWatcher_.isRunning() || importCancelled_) return;
  importBusy_->setRange(0, 1000);
  importBusy_->setValue(int(std::lround(fraction * 1000)));
  statusBar()->showMessage(tr("Importing %1: %2").arg(QFileInfo(importPath_).fileName(), stage));
}

void MainWindow::waitImport() {
  if (importWatcher_.isRunning()) importWatcher_.waitForFinished();
  QCoreApplication::processEvents();  // delivers finished()
}

// Cancel gives the window back at once; the worker stops at the reading's, the repair's or the validation's
// next check (ReadOptions::progress, RepairOptions::progress, StageProgress: within about a second at every
// stage) and whatever it returns is discarded.
void MainWindow::cancelImport() {
  if (!importWatcher_.isRunning()) return;
  importCancelled_ = true;
  if (importStop_) importStop_->store(true);
  importBusy_->setVisible(false);
  importCancel_->setVisible(false);
  statusBar()->showMessage(tr("Import of %1 cancelled").arg(QFileInfo(importPath_).fileName()), 5000);
}

void MainWindow::importFinished() {
  importBusy_->setVisible(false);
  importCancel_->setVisible(false);
  ImportOutcome out = importWatcher_.result();
  importStoppedAt_ = out.stoppedAt;
  if (std::exchange(importCancelled_, false)) return;
  if (!out.error.isEmpty()) {
    showError(tr("Cannot open %1").arg(QFileInfo(importPath_).fileName()), out.error);
    return;
  }
  if (out.bone.mesh.triangles.empty()) {
    showError(tr("Cannot open %1").arg(QFileInfo(importPath_).fileName()), importPath_ + ": the mesh has no triangles");
    return;
  }
  try {
    if (!session_->reamer()->cuttingVolume()) session_->setReamer(loadPreset(kDefaultReamerPreset, reamerPresetsPath()));
    const Bounds b = BoneState::fromMesh(out.bone.mesh).bounds();
    const BoneFileFacts saved = out.bone.saved;
    session_->plan()->setPoses({});
    installBone(std::move(out.bone), QFileInfo(importPath_).fileName(), importPath_);
    const AdoptedHistory history = adoptSavedHistory(out, saved, importPath_);
    openLandmarksBeside(importPath_);
    const QString withLog = openCutLogBeside(importPath_, saved, history);
    session_->moveReamer(startPoseFor(b));
    const QString withHistory = history.steps == 0 ? QString()
                                : history.steps == 1 ? tr(", and its undo history (1 step)")
                                                     : tr(", and its undo history (%1 steps)").arg(history.steps);
    statusBar()->showMessage(tr("Opened %1").arg(importPath_) + withLog + withHistory,
                             withLog.isEmpty() && withHistory.isEmpty() ? 5000 : 15000);
  } catch (const std::exception& e) {  // e.g. the reamer presets file is missing or broken
    showError(tr("Cannot open %1").arg(QFileInfo(importPath_).fileName()), QString::fromStdString(e.what()));
  }
}

void MainWindow::installBone(ImportedBone bone, const QString& name, const QString& recentPath) {
  const Pose start = session_->reamer()->pose();
  const PatientFrame frame = bone.frame;
  std::string source = bone.source;
  session_->loadBone(std::move(bone), name, start);
  session_->bone()->setPatientFrame(frame);  // loadBone predates the frame: set here (docs/CT_IMPORT.md)
  session_->bone()->setSource(std::move(source));
  boneName_ = name;
  savedPath_.clear();  // another bone: Save asks where
  savedPlanning_ = planningOf(*session_->bone());  // none (loadBone clears them): the caller may bring some
  savedNotes_ = {session_->log()->id(), session_->log()->notesRevision(), {}};  // a new log
  savedBoneRevision_ = session_->bone()->currentRevision();  // as opened
  ++boneGeneration_;
  if (!recentPath.isEmpty()) addRecent(recentPath);
  updateTitle();
  updateStatus();
}

bool MainWindow::saveBoneAs(const QString& path) {
  // The bone and its log as they are now. A step that lands while the file is written (a queued feed) is
  // in neither, and the bone is then not marked saved.
  bool changedMeanwhile = false;
  const std::uint64_t generation = boneGeneration_;
  const QMetaObject::Connection watch =
      connect(session_->undoStack(), &QUndoStack::indexChanged, this, [&changedMeanwhile] { changedMeanwhile = true; });
  const std::string csv = cutLogCsv(withUndoneMarked(session_->log()->entries(), session_->bone()->history()));
  const SavedNotes notes = notesOf(*session_->log());
  const BonePlanning planning = planningOf(*session_->bone());
  // What reopening the bone needs to continue this log: the volume removed before this state (undone cuts not
  // counted) and the log's length, to tell it from another log put beside the bone later; and to undo and redo
  // its cuts again, its undo history (its states share storage: a copy is cheap), and where in it the bone is.
  const std::vector<CutLogEntry>& rows = session_->log()->entries();
  const BoneHistory& history = session_->bone()->history();
  BoneFileFacts facts = BoneFileFacts::ofFrame(session_->bone()->patientFrame());
  facts.removedMm3 = session_->initialVolumeMm3() - session_->bone()->current().volume();
  facts.cutLogRows = rows.size();
  facts.cutLogLastMs = rows.empty() ? 0 : rows.back().timeUnixMs;
  std::vector<BoneHistory::Entry> states = statesToSave(history, *session_->undoStack());
  const bool historyLeftOut = states.size() >= 2 && !keepsExactCoordinates(path);
  if (states.size() >= 2 && !historyLeftOut) {
    facts.historyStates = states.size();
    facts.historyCursor = history.cursor();
  } else {
    states.clear();
  }
  // A history there that could not be read when the bone was opened is the user's to look at: kept aside.
  const QString historyPath = historyPathBeside(path);
  try {
    moveAsideIfRefused(historyPath, unreadableHistoryFile_);
  } catch (const std::exception& e) {
    disconnect(watch);
    showError(tr("Cannot save %1").arg(QFileInfo(path).fileName()), QString::fromStdString(e.what()));
    return false;
  }
  const bool written = writeBoneFile(path, facts, states);
  disconnect(watch);
  if (!written) return false;
  if (generation != boneGeneration_) {  // an import finished meanwhile: the file holds the bone that was there
    showError(tr("Save"), tr("%1 holds the bone as it was when saving began; another bone has been opened since, "
                             "and it is not saved.").arg(path));
    return false;
  }
  const QString logPath = cutLogPathBeside(path);
  try {
    moveAsideIfRefused(logPath, unreadableCutLogFile_);
    writeTextFile(logPath.toStdString(), csv);
  } catch (const std::exception& e) {
    // The bone is written but its log is not: the work is not saved yet (closing asks again).
    showError(tr("Cannot save the cut log %1").arg(QFileInfo(logPath).fileName()), QString::fromStdString(e.what()));
    return false;
  }
  // The landmarks beside, or no file there: one left from an earlier save would come back on the next open.
  const QString landmarksPath = landmarksPathBeside(path);
  try {
    // A file there that could not be read when the bone was opened is the user's to look at: kept aside, never
    // replaced or removed.
    moveAsideIfRefused(landmarksPath, unreadablePlanningFile_);
    if (planning != BonePlanning{})
      writeTextFile(landmarksPath.toStdString(), planningToJson(planning, "saved with the bone by ReamSim"));
    else if (QFileInfo::exists(landmarksPath) && !QFile::remove(landmarksPath))
      throw std::runtime_error(landmarksPath.toStdString() + ": cannot remove the landmarks of an earlier save");
  } catch (const std::exception& e) {
    showError(tr("Cannot save the landmarks %1").arg(QFileInfo(landmarksPath).fileName()), QString::fromStdString(e.what()));
    return false;
  }
  // No undo history to save (written with the bone otherwise): none left beside from an earlier save either.
  if (!facts.historyStates && QFileInfo::exists(historyPath) && !QFile::remove(historyPath)) {
    showError(tr("Cannot save %1").arg(QFileInfo(path).fileName()),
              tr("%1: cannot remove the undo history of an earlier save").arg(historyPath));
    return false;
  }
  savedPlanning_ = planning;
  savedNotes_ = notes;
  QString roomNote = factsLeftOut(path, facts);
  if (historyLeftOut)
    roomNote += tr(". A binary STL keeps coordinates in single precision: the undo history is not saved with it "
                   "(reopened, Undo starts there; PLY, OBJ, OFF, VTP or ASCII STL keep it)");
  updateTitle();  // landmarks or notes alone changed: the undo stack's clean state did not move
  // Nor did the copy kept for a crash: written again (or removed, when nothing is left unsaved).
  if (recovery_ && !recoveryOfferPending_ && !recoveryTimer_.isActive()) recoveryTimer_.start();
  savedPath_ = path;  // written: the next Save goes here too
  if (changedMeanwhile) {
    statusBar()->showMessage(tr("Saved %1 and its cut log as they were when saving began; later cuts are not saved")
                                 .arg(path) + roomNote, 15000);
    return true;
  }
  session_->undoStack()->setClean();
  savedBoneRevision_ = session_->bone()->currentRevision();
  updateTitle();  // the stack may have been clean already (only landmark edits since the last save)
  savedRevisions_.insert(session_->bone()->currentRevision());  // still saved if it is later moved beside
  statusBar()->showMessage(tr("Saved %1 and its cut log").arg(path) + roomNote, roomNote.isEmpty() ? 5000 : 20000);
  return true;
}

// What a save's file has no room for (a binary STL's 80-byte header), said after "Saved …": without the log's
// record, reopening the bone does not bring its log back; without the removed volume, the log's cumulative volume
// goes on from its last row.
QString MainWindow::factsLeftOut(const QString& path, const BoneFileFacts& facts) {
  WriteOptions options;  // as the plugin writes (binary where the format has a choice)
  options.comments = factComments(facts);
  const std::vector<std::string> kept = commentsKept(path.toStdString(), options);
  const auto keeps = [&kept](std::string_view prefix) {
    return std::any_of(kept.begin(), kept.end(), [prefix](const std::string& c) { return c.rfind(prefix, 0) == 0; });
  };
  QString out;
  if (facts.cutLogRows && !keeps(bone_file_facts::kCutLog))
    out = tr(". The file has no room to record the cut log saved beside it: reopened, it comes without its log");
  else if (facts.removedMm3 && facts.cutLogRows && *facts.cutLogRows > 0 && !keeps(bone_file_facts::kRemoved))
    out = tr(". The file has no room for the volume removed so far: reopened, its log's cumulative volume goes on "
             "from the log's last row");
  return out.isEmpty() ? out : out + tr(" (PLY, OBJ, OFF, VTP or ASCII STL keep it)");
}

bool MainWindow::saveBone() { return savedPath_.isEmpty() ? saveBoneAndCutLogInteractive() : saveBoneAs(savedPath_); }

// Encoding and writing a bone take 0.2 s at 405k faces and seconds at millions (a CT bone repaired at 0.5 mm
// has 17 million): done on a worker, with a window-modal dialog that shows how far it is and can cancel,
// while this waits in a local event loop (the window keeps painting). Cancel keeps the file that was there.
bool MainWindow::writeBoneFile(const QString& path, const BoneFileFacts& facts,
                               const std::vector<BoneHistory::Entry>& history) {
  if (!plugins_.meshImport()) {
    showError(tr("Save"), tr("Cannot save %1: no mesh import plugin is loaded (Help → Plugins).").arg(path));
    return false;
  }
  if (saving_) {  // not reachable through the blocked window; a guard for programmatic calls
    showError(tr("Save"), tr("Cannot save %1: another file is being written.").arg(path));
    return false;
  }
  struct Outcome {
    bool cancelled = false;
    QString error;
  };
  const MeshImportInterface* writer = plugins_.meshImport();
  BoneState state = session_->bone()->current();  // an immutable value, cheap to copy
  std::vector<BoneHistory::Entry> states = history;  // they share storage: cheap to copy too
  const QString name = QFileInfo(path).fileName();
  WriteProgressDialog dialog(tr("Saving %1").arg(name), this);
  saving_ = true;
  const Outcome out = dialog.runWhileShown(
      [writer, state = std::move(state), states = std::move(states), file = path, facts](const ProgressCallback& progress) {
        Outcome result;
        QString historyPart;
        try {
          // The undo history first, beside (12 MB at 405k faces, tens of ms), put in place only once the bone
          // file is: a save that stops or fails on the way leaves both files that were there.
          if (!states.empty()) {
            if (progress && !progress(0.0, "undo history")) throw WriteCancelled("undo history");
            historyPart = writeSavedHistoryPart(historyPathBeside(file), states, file);
          }
          writer->exportMesh(state.toMesh(), file.toStdString(), facts, progress);
          if (!historyPart.isEmpty())
            commitSavedHistory(std::exchange(historyPart, QString()), historyPathBeside(file), file);
        } catch (const WriteCancelled&) {
          result.cancelled = true;
        } catch (const std::exception& e) {
          result.error = QString::fromStdString(e.what());
        }
        discardSavedHistory(historyPart);  // stopped or failed before it was put in place
        return result;
      });
  saving_ = false;
  if (out.cancelled) {
    statusBar()->showMessage(tr("Save of %1 cancelled; the file there is unchanged").arg(name), 8000);
    return false;
  }
  if (!out.error.isEmpty()) {
    showError(tr("Cannot save %1").arg(name), out.error);
    return false;
  }
  return true;
}

// The bone itself away from the state it was opened or saved in (revisions are never reused, so undone back to
// it, it is as saved). Not the undo stack's clean point: landmark edits are on the stack too (PlanningCommand).
bool MainWindow::boneChangedSinceSave() const {
  return !savedBoneRevision_ || session_->bone()->currentRevision() != *savedBoneRevision_;
}

// The bone changed since it was saved, or its landmarks or the notes on its cuts (saved beside it).
bool MainWindow::hasUnsavedChanges() const {
  return boneChangedSinceSave() || planningOf(*session_->bone()) != savedPlanning_ ||
         notesChangedSinceSave();
}

// A log other than the one saved (a new bone's) has changed only once a note was written on it; then, notes
// written and undone (NoteCommand) back to what was saved are no change. A row added since the save is compared
// with no note (a plan's note on it, part of its cut, then counts too: the cut is unsaved work anyway).
bool MainWindow::notesChangedSinceSave() const {
  const LogNode& log = *session_->log();
  const bool savedLog = log.id() == savedNotes_.log;
  if (log.notesRevision() == (savedLog ? savedNotes_.revision : 0)) return false;  // none written since
  const std::vector<CutLogEntry>& rows = log.entries();
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].note != (savedLog && i < savedNotes_.notes.size() ? savedNotes_.notes[i] : std::string())) return true;
  return false;
}

MainWindow::SavedNotes MainWindow::notesOf(const LogNode& log) {
  SavedNotes out{log.id(), log.notesRevision(), {}};
  for (const CutLogEntry& e : log.entries()) out.notes.push_back(e.note);
  return out;
}

// The mesh file's whole name, so that scapula.stl and scapula.ply beside it never share one.
QString MainWindow::landmarksPathBeside(const QString& bonePath) { return bonePath + ".landmarks.json"; }

// A bone opened from a file brings the landmarks saved beside it (NAME.landmarks.json), if any: they are part
// of the work saved with it. One that cannot be read is named in the status bar; the bone opens without them.
void MainWindow::openLandmarksBeside(const QString& bonePath) {
  const QString file = landmarksPathBeside(bonePath);
  unreadablePlanningFile_.clear();
  if (!QFileInfo::exists(file)) return;
  try {
    const BonePlanning planning = loadPlanning(file.toStdString());
    const ReamSession::QuietPlanning quiet(*session_);  // saved with the bone: not an edit to undo
    applyPlanning(*session_->bone(), planning);
    savedPlanning_ = planning;
    updateTitle();
  } catch (const std::exception& e) {
    unreadablePlanningFile_ = file;  // a save keeps it aside instead of replacing it
    showError(tr("Landmarks not read"),
              tr("%1\n\nThe bone opens without landmarks; %2.").arg(QString::fromStdString(e.what()), keptAsideNote(file)));
  }
}

// The bone file's whole name, as for its landmarks: NAME.stl and NAME.ply saved side by side keep a log each.
QString MainWindow::cutLogPathBeside(const QString& bonePath) { return bonePath + ".cut_log.csv"; }

// Where saves before session 57 put it (NAME.cut_log.csv beside NAME.ply): read when the bone has no log of
// the name above, never written.
QString MainWindow::earlierCutLogPathBeside(const QString& bonePath) {
  const QFileInfo info(bonePath);
  return info.dir().filePath(info.completeBaseName() + ".cut_log.csv");
}

QString MainWindow::keptAsideNote(const QString& file) {
  return tr("the file stays as it is (a save moves it aside to %1)").arg(QFileInfo(file).fileName() + ".unreadable");
}

void MainWindow::moveAsideIfRefused(const QString& file, QString& refused) {
  if (file != refused || !QFileInfo::exists(file)) return;
  QString aside = file + ".unreadable";
  for (int n = 2; QFileInfo::exists(aside); ++n) aside = file + ".unreadable." + QString::number(n);
  if (!QFile::rename(file, aside)) throw std::runtime_error(file.toStdString() + ": cannot move the unreadable file aside");
  refused.clear();
}

void MainWindow::stackAdoptedSteps(const QString& when) {
  const BoneHistory& adopted = session_->bone()->history();
  for (std::size_t k = 1; k < adopted.size(); ++k) {
    const BoneState& before = adopted.entries()[k - 1].state;
    const BoneState& after = adopted.entries()[k].state;
    session_->undoStack()->push(new CutCommand(*session_->bone(), tr("%1 (%2): %L3 mm³, %L4 faces")
                                                                      .arg(QString::fromStdString(adopted.entries()[k].label), when)
                                                                      .arg(before.volume() - after.volume(), 0, 'f', 2)
                                                                      .arg(after.liveTriangleCount())));
  }
}

// Since session 57 a save writes the bone's undo history beside it: the reopened bone undoes the cuts made before
// the save (down to the bone first opened) and redoes those undone before it. The history's state at the save is
// the bone as read (readSavedHistory checks it); the bone takes the history's exact coordinates. Opened so, the
// bone is as saved: the stack's clean point is the save's state.
AdoptedHistory MainWindow::adoptSavedHistory(ImportOutcome& out, const BoneFileFacts& saved, const QString& bonePath) {
  AdoptedHistory adopted;
  unreadableHistoryFile_.clear();
  if (!out.historyError.isEmpty()) {
    const QString file = historyPathBeside(bonePath);
    const bool there = QFileInfo::exists(file);
    if (there) unreadableHistoryFile_ = file;  // a save keeps it aside instead of replacing or removing it
    showError(tr("Undo history not read"),
              there ? tr("%1\n\nThe bone opens without it: Undo cannot go back before it; %2.").arg(out.historyError, keptAsideNote(file))
                    : tr("%1\n\nThe bone opens without it: Undo cannot go back before it.").arg(out.historyError));
  }
  if (!out.history) return adopted;
  const std::size_t cursor = saved.historyCursor;
  const std::vector<std::uint64_t> written = std::move(out.history->writtenRevisions);
  session_->adoptHistory(std::move(out.history->history));
  out.history.reset();
  const BoneHistory& history = session_->bone()->history();
  for (std::size_t k = 0; k < history.size() && k < written.size(); ++k)
    adopted.revisions[written[k]] = history.entries()[k].revision;
  stackAdoptedSteps(tr("before the save"));
  session_->undoStack()->setIndex(int(cursor));  // undoes what had been undone before the save
  session_->undoStack()->setClean();
  session_->restartPath(ReamSession::PathStart::AsOpened);
  savedBoneRevision_ = session_->bone()->currentRevision();
  savedRevisions_.insert(*savedBoneRevision_);
  adopted.removedSinceFirstMm3 = history.entries().front().state.volume() - session_->bone()->current().volume();
  adopted.steps = session_->undoStack()->count();
  updateTitle();  // the stack's index moved before the saved revision did
  return adopted;
}

// A bone opened from a file its Save wrote brings the cut log saved beside it (NAME.ply.cut_log.csv, or
// NAME.cut_log.csv as saves before session 57 named it): the log panel lists its rows with their notes, new steps
// continue its numbering, and the cumulative volume goes on from what had been removed when the bone was saved
// (the file's `removed_mm3`). Only a file whose save recorded the log (`cut_log`) takes one: a raw scan beside a
// reamed save of the same name never does. A log that cannot be read, or is not the one saved (another number of
// rows or another last time: another save's, or the bone replaced since), or is missing, is named in a dialog;
// the bone opens without it, and a save to NAME.ply moves a file at NAME.ply.cut_log.csv aside instead of
// replacing it (an earlier save's NAME.cut_log.csv is never written). Returns what the status bar adds to
// "Opened …" (empty without a log).
QString MainWindow::openCutLogBeside(const QString& bonePath, const BoneFileFacts& saved, const AdoptedHistory& history) {
  const auto rowsText = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " row" : " rows"); };
  QString file = cutLogPathBeside(bonePath);
  if (!QFileInfo::exists(file) && QFileInfo::exists(earlierCutLogPathBeside(bonePath)))
    file = earlierCutLogPathBeside(bonePath);
  unreadableCutLogFile_.clear();
  if (!saved.cutLogRows) return {};  // not a bone a Save wrote (or saved before session 56)
  const std::string bone = QFileInfo(bonePath).fileName().toStdString();
  std::vector<CutLogEntry> rows;
  try {
    if (!QFileInfo::exists(file)) {
      if (*saved.cutLogRows == 0) return {};
      throw std::runtime_error(file.toStdString() + ": not found (nor " +
                               QFileInfo(earlierCutLogPathBeside(bonePath)).fileName().toStdString() + "); " + bone +
                               " was saved with its cut log there (" + rowsText(*saved.cutLogRows) + ")");
    }
    rows = readCutLogCsv(file.toStdString());
    if (rows.size() != *saved.cutLogRows || (!rows.empty() && rows.back().timeUnixMs != saved.cutLogLastMs))
      throw std::runtime_error(file.toStdString() + ": not the cut log saved with " + bone + " (" +
                               rowsText(rows.size()) + ", the last at " +
                               (rows.empty() ? std::string("-") : std::to_string(rows.back().timeUnixMs)) +
                               " ms; saved: " + rowsText(*saved.cutLogRows) + ", the last at " +
                               std::to_string(saved.cutLogLastMs) + " ms)");
  } catch (const std::exception& e) {
    const bool there = QFileInfo::exists(file);
    const bool earlierName = file != cutLogPathBeside(bonePath);  // never written by a save: nothing to move aside
    if (there && !earlierName) unreadableCutLogFile_ = file;
    const QString what = QString::fromStdString(e.what());
    showError(tr("Cut log not read"),
              !there ? tr("%1\n\nThe bone opens without its cut log.").arg(what)
              : earlierName
                  ? tr("%1\n\nThe bone opens without its cut log; the file stays as it is (a save writes the log as %2).")
                        .arg(what, QFileInfo(cutLogPathBeside(bonePath)).fileName())
                  : tr("%1\n\nThe bone opens without its cut log; %2.").arg(what, keptAsideNote(file)));
    return {};
  }
  if (rows.empty()) return {};
  const std::size_t count = rows.size();
  // Removed before the history's first state: what the save recorded (a binary STL may have had no room for it:
  // then the last row's cumulative volume), less the cuts between that state and the bone as saved when a saved
  // undo history came back.
  std::optional<double> removedBefore = saved.removedMm3;
  if (!history.revisions.empty())
    removedBefore = removedBefore.value_or(rows.back().cumulativeMm3) - history.removedSinceFirstMm3;
  session_->continueLog(std::move(rows), removedBefore, history.revisions);
  savedNotes_ = notesOf(*session_->log());  // as saved
  updateTitle();
  const QString steps = count == 1 ? tr("1 step") : tr("%1 steps").arg(count);
  if (saved.removedMm3) return tr(" with its cut log (%1)").arg(steps);
  // A binary STL's header had no room for it: the log's last row is the best left (too high by any cut
  // undone before the save).
  return tr(" with its cut log (%1; the file has no room for the volume removed at the save: the cumulative "
            "volume goes on from the log's last row)").arg(steps);
}

// A bone that is not the cut one holds work no save wrote: cuts in its history, or a crash copy restored, and
// its state was not written by a save (of when it was the cut bone).
bool MainWindow::unsavedOutsideTheCutBone(const BoneHistory& history) const {
  if (savedRevisions_.count(history.currentRevision())) return false;
  return history.cursor() > 0 || recoveredRevisions_.count(history.entries().front().revision) > 0;
}

std::vector<const BoneNode*> MainWindow::unsavedBonesBeside() const {
  std::vector<const BoneNode*> out;
  for (const BoneNode* other : session_->document().nodesOf<BoneNode>())
    if (other != session_->bone() && unsavedOutsideTheCutBone(other->history())) out.push_back(other);
  return out;
}

QStringList MainWindow::bonesBesideWithUnsavedCuts() const {
  QStringList names;
  for (const BoneNode* other : unsavedBonesBeside()) names << QString::fromStdString(other->name());
  return names;
}

std::vector<const BoneContent*> MainWindow::unsavedReplacedBones() const {
  std::vector<const BoneContent*> out;
  const QUndoStack* stack = session_->undoStack();
  for (int i = 0; i < stack->count(); ++i) {
    const auto* replace = dynamic_cast<const ReplaceBoneCommand*>(stack->command(i));
    if (replace && unsavedOutsideTheCutBone(replace->held().history)) out.push_back(&replace->held());
  }
  return out;
}

QStringList MainWindow::replacedBonesWithUnsavedCuts() const {
  QStringList names;
  for (const BoneContent* replaced : unsavedReplacedBones()) names << QString::fromStdString(replaced->name);
  return names;
}

// Save writes the cut bone only; a bone moved beside it (Cut a bone beside instead) or replaced by an import may
// keep cuts of its own.
bool MainWindow::confirmDiscardBonesBeside(const QString& action) {
  QStringList items;
  for (const QString& n : bonesBesideWithUnsavedCuts()) items << tr("%1 (beside the cut bone)").arg(n);
  for (const QString& n : replacedBonesWithUnsavedCuts()) items << tr("%1 (replaced by a CT import)").arg(n);
  if (items.isEmpty()) return true;
  QMessageBox box(QMessageBox::Warning, tr("Unsaved bones"), tr("Cuts that are not saved: %1.").arg(items.join(", ")),
                  QMessageBox::Discard | QMessageBox::Cancel, this);
  box.setObjectName("UnsavedBonesBesideDialog");
  box.setInformativeText(tr("Only the cut bone is saved. To keep a bone beside, cancel, make it the cut bone (File → "
                            "Cut a bone beside instead) and save it; to keep a replaced bone, cancel and undo the "
                            "import. Discard their cuts and %1?").arg(action));
  box.setDefaultButton(QMessageBox::Cancel);
  return box.exec() == QMessageBox::Discard;
}

void MainWindow::closeEvent(QCloseEvent* e) {
  // A file being written finishes first; the bones beside are asked about after the cut bone.
  if (saving_ || !confirmDiscardChanges(tr("close ReamSim")) || !confirmDiscardBonesBeside(tr("close ReamSim"))) {
    e->ignore();
    return;
  }
  endRecovery();  // a normal close: no copy to offer next time
  e->accept();
}

bool MainWindow::confirmDiscardChanges(const QString& action) {
  if (session_->busy()) {  // the step in flight would change the bone after the answer
    session_->cancelQueued();
    session_->waitIdle(60000);
  }
  if (!hasUnsavedChanges()) return true;
  const QString name = boneName_.isEmpty() ? tr("The bone") : tr("The bone (%1)").arg(boneName_);
  const std::size_t cuts = session_->log()->entries().size();
  QStringList what;  // since it was opened or last saved
  if (boneChangedSinceSave()) what << tr("the bone has changed");
  if (planningOf(*session_->bone()) != savedPlanning_) what << tr("its landmarks or planned axis have changed");
  if (notesChangedSinceSave()) what << tr("notes on its cuts have changed");
  QMessageBox box(QMessageBox::Warning, tr("Unsaved changes"),
                  tr("%1 is not saved: %2 since it was opened or last saved (its cut log holds %3).")
                      .arg(name, what.join(tr("; ")), cuts == 1 ? tr("1 cut") : tr("%1 cuts").arg(cuts)),
                  QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
  box.setObjectName("UnsavedChangesDialog");
  box.setInformativeText(tr("Save the bone, and its cut log beside it, before you %1?").arg(action));
  box.setDefaultButton(QMessageBox::Save);
  switch (box.exec()) {
    case QMessageBox::Save:
      return saveBone();
    case QMessageBox::Discard:
      return true;
    default:
      return false;
  }
}

// The bone where the user says, the cut log as NAME.ply.cut_log.csv beside it. Anything that fails (or a
// cancelled file dialog) answers false, so the window stays as it is and nothing is lost.
bool MainWindow::saveBoneAndCutLogInteractive() {
  if (!plugins_.meshImport()) {
    showError(tr("Save"), tr("No mesh import plugin is loaded (Help → Plugins): the bone cannot be saved."));
    return false;
  }
  const QString path = QFileDialog::getSaveFileName(this, tr("Save bone mesh"), "bone.ply",
                                                    plugins_.meshImport()->nameFilters().join(";;"));
  return !path.isEmpty() && saveBoneAs(path);
}

void MainWindow::addRecent(const QString& path) {
  const QString full = QFileInfo(path).absoluteFilePath();
  recent_.removeAll(full);
  recent_.prepend(full);
  while (recent_.size() > kMaxRecent) recent_.removeLast();
  if (persistent_) QSettings().setValue("recent_files", recent_);
}

void MainWindow::rebuildRecentMenu() {
  recentMenu_->clear();
  for (const QString& path : recent_) {
    QAction* a = recentMenu_->addAction(path);
    connect(a, &QAction::triggered, this, [this, path] {
      if (confirmDiscardChanges(tr("open another bone"))) openFile(path, true);
    });
  }
  if (recent_.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
  if (e->mimeData()->hasUrls() && !e->mimeData()->urls().isEmpty() && e->mimeData()->urls().front().isLocalFile())
    e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
  const QList<QUrl> urls = e->mimeData()->urls();
  if (urls.isEmpty() || !urls.front().isLocalFile()) return;
  e->acceptProposedAction();
  if (confirmDiscardChanges(tr("open another bone"))) openFile(urls.front().toLocalFile(), true);
}

QString MainWindow::exportReport(const QString& file) {
  const BoneNode& bone = *session_->bone();
  ReamReportInput in;
  in.boneName = boneName_.toStdString();
  in.boneSource = bone.source();
  in.patientFrame = bone.patientFrame();
  in.volumeAtStartMm3 = session_->initialVolumeMm3();
  in.volumeNowMm3 = bone.current().volume();
  in.facesAtStart = bone.history().entries().front().state.liveTriangleCount();
  in.facesNow = bone.current().liveTriangleCount();
  in.reamer = session_->reamer()->spec();
  if (session_->reamer()->cuttingVolume()) in.reamerPose = session_->reamer()->pose();
  in.landmarks = bone.landmarks();
  in.plannedAxis = bone.plannedAxis();
  addGlenoidFaces(in, bone.history().entries().front().state, bone.current());
  try {
    addSeat(in, bone.current());
  } catch (const std::invalid_argument&) {  // a spec the measure refuses: the report goes without the seat
  }
  // The log only grows: a cut undone since (its state in this bone's history, past the cursor) is marked, and so
  // is one a saved log said was undone. Rows of another bone (before an exchange) or of a branch the history left
  // are not this history's: not marked.
  in.cuts = withUndoneMarked(session_->log()->entries(), bone.history());
  for (const CutLogEntry& e : in.cuts) in.undone.push_back(e.undone);
  in.writtenUnixMs = QDateTime::currentMSecsSinceEpoch();
  in.writtenBy = "ReamSim (File → Export a report)";
  // The view as it is drawn now: the bone, its removed depth or fresh cuts, the reamer, the landmarks.
  QByteArray png;
  QBuffer buffer(&png);
  buffer.open(QIODevice::WriteOnly);
  if (view_->grabFramebuffer().save(&buffer, "PNG")) in.pngBase64 = png.toBase64().toStdString();
  return writeTextReporting(file, reamReportHtml(in));
}

QString MainWindow::writeTextReporting(const QString& file, const std::string& text) {
  try {
    writeTextFile(file.toStdString(), text);
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

void MainWindow::exportReportInteractive() {
  const QString file = QFileDialog::getSaveFileName(this, tr("Export a report"), "reaming_report.html", tr("HTML (*.html)"));
  if (file.isEmpty()) return;
  const QString error = exportReport(file);
  if (!error.isEmpty()) return showError(tr("Export a report"), error);
  statusBar()->showMessage(tr("Report written to %1").arg(file), 8000);
}

}  // namespace reamsim::ui
