#pragma once
// The ReamSim main window: the 3D view, the reamer controls (thesis keys, remappable), live cutting
// through the ReamSession, undo/redo with a history view, file open/save (via the mesh import plugin),
// drag and drop, recent files, the plugin panels (log) and Help → Plugins.
#include <QFutureWatcher>
#include <QMainWindow>
#include <QTimer>
#include <QMap>
#include <QStringList>
#include <atomic>
#include <memory>
#include <set>
#include <unordered_map>
#include <optional>

#include "BoneView.h"
#include "ReamerMotion.h"
#include "ReamSession.h"
#include "RecoveryRead.h"
#include "SavedHistory.h"
#include "reamsim/ream/ScapularFrame.h"

class QAction;
class QActionGroup;
class QDialog;
class QDoubleSpinBox;
class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;
class QSettings;
class QDockWidget;

namespace reamsim {
class HistoryJournalWriter;
}

namespace reamsim::ui {

class OtherBonesLayer;
class PluginHost;
class RecoveryFiles;
struct RecoveredBone;

struct ImportOutcome {
  ImportedBone bone;
  QString error;
  QString stoppedAt;  // the repair's stage where a cancelled import's worker stopped
  // The undo history a save wrote beside the file (BoneFileFacts::historyStates), read on the worker too; or why
  // it could not be.
  std::optional<SavedHistoryRead> history;
  QString historyError;
};

// A saved undo history adopted by an opened bone: the saved log's revisions become its states' (continueLog),
// and the log's removed volume is counted from its first state.
struct AdoptedHistory {
  std::unordered_map<std::uint64_t, std::uint64_t> revisions;  // written → adopted, state by state
  double removedSinceFirstMm3 = 0;  // from the history's first state to the bone as opened
  int steps = 0;                    // undo steps it brings
};

// How a plan's steps are run: as fast as they compute, or each timed pose at its recorded time (t_ms: a path
// exported from a session) at the window's replay speed; a plan without times cannot be replayed at its pace.
enum class PlanPace { AsFastAsComputed, AsRecorded };

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  // useStoredSettings = false: defaults only, nothing read from or written to QSettings (demo,
  // benchmark, tests: reproducible pictures and numbers).
  MainWindow(const PluginHost& plugins, bool useStoredSettings, QWidget* parent = nullptr);
  ~MainWindow() override;

  ReamSession& session() { return *session_; }
  BoneView* view() const { return view_; }
  const PluginHost& plugins() const { return plugins_; }
  QAction* moveAction(ReamerMove move) const { return moveActions_.value(static_cast<int>(move)); }
  QAction* action(const QString& objectName) const;
  const QString& lastError() const { return lastError_; }
  QStringList recentFiles() const { return recent_; }
  QString statusAlertText() const;
  QString statusDistanceText() const;

  void setSteps(double moveMm, double rotateDeg, double feedMm);
  double feedStepMm() const;
  // Refused (false, with an error dialog) when another action already has `keys`.
  bool setKeyBinding(ReamerMove move, const QKeySequence& keys);
  QString shortcutOwner(const QKeySequence& keys, const QList<const QAction*>& ignored) const;

 public Q_SLOTS:
  bool loadDefaultCase();
  void openFile(const QString& path, bool repair = true);
  bool importRunning() const { return importWatcher_.isRunning(); }
  void waitImport();
  void cancelImport();  // the window is free at once; the worker stops at its next check, its result is discarded
  // Where the last cancelled import's worker stopped (a repair stage), empty when it ran to its end (tests).
  const QString& lastImportStoppedAt() const { return importStoppedAt_; }
  // The bone at `path` and its cut log beside it (NAME.ply.cut_log.csv); true when both are written, and only then
  // is the bone "saved" (no unsaved changes). Errors in a dialog.
  bool saveBoneAs(const QString& path);
  // File → Save (Ctrl+S) and the close question's Save: to the file the bone was last saved to with Save as
  // (never over the file it was opened from: that is the unrepaired original), else Save as.
  bool saveBone();
  const QString& savedPath() const { return savedPath_; }  // empty until Save as wrote this bone
  // Changes since the bone was opened or last saved: the bone, its landmarks and planned axis, the notes on its cuts.
  bool hasUnsavedChanges() const;
  bool boneChangedSinceSave() const;  // the cut bone, not its landmarks or notes
  bool notesChangedSinceSave() const;
  // Bones beside with cuts in their history whose state no save wrote (their names): Save writes the cut bone only.
  QStringList bonesBesideWithUnsavedCuts() const;
  // Bones replaced by a CT import (held by the undo history) with cuts no save wrote (their names).
  QStringList replacedBonesWithUnsavedCuts() const;
  // Depth below the first contact along the axis (searched on a worker, then fed in feed steps).
  void reamToDepth(double depthMm);
  bool contactSearchRunning() const { return pendingDepth_.has_value(); }
  double lastApproachMm() const { return lastApproachMm_; }  // of the last reamToDepth (tests)
  // Feed along the axis by `mm` from where the last queued step ends, in feed steps.
  void feedBy(double mm);
  void applyMove(ReamerMove move);
  void dragReamer(double mm);
  // The reamer (a preset of reamers.json; empty: the user picks one from the list). The reamer keeps its
  // pose; the next cut is made, and logged, with the new one. False when nothing changed (cancelled, unknown).
  bool chooseReamer(const QString& preset = {});
  // A reamer read from a mesh (a closed solid, tip at the origin, feed along +Z; empty: the user picks the file),
  // as `reamsim-cli ream --reamer FILE`. False, with a message naming the file and the problem, when it cannot be.
  bool chooseReamerMesh(const QString& path = {});
  // The reamer moves' keys stored under keys/ (a user's window reads them at start): one that a menu action has
  // taken is not used (the move keeps its default key) and the status bar names it.
  void applyStoredKeyBindings(const QSettings& settings);
  // The reamer's path on this bone (ReamSession::path) as a plan file that replays it (docs/PLAN_FORMAT.md,
  // "placed"): an error message naming the file or the problem, empty when written.
  QString exportPath(const QString& file);
  void exportPathInteractive();
  // A reaming report for review (reamsim/ream/ReamReport.h: one HTML file with the bone, the reamer, the landmarks
  // and the axis's version and inclination, the cuts, and a picture of the view): an error message naming the
  // file, empty when written.
  QString exportReport(const QString& file);
  void exportReportInteractive();
  // Runs a plan file (docs/PLAN_FORMAT.md) on the bone as `reamsim-cli ream --plan` does: its reamer (a
  // preset) is taken, the reamer is placed at the first pose (and at every pose marked "placed") and follows
  // the rest as a path (sideways moves sweep), as fast as the steps compute or at the pace they were recorded
  // at (PlanPace). An empty path: the user picks the file. False (with a message naming the file and the
  // problem) when the plan cannot be run.
  bool runPlanFile(const QString& path = {}, PlanPace pace = PlanPace::AsFastAsComputed);
  // How much bone "ream to depth" of depthMm from the reamer's pose would remove, computed on a copy of the bone
  // (ReamSession::previewReamToDepth) and shown with a *Ream it* button; Stop (Esc) stops it. The answer's
  // text is also lastPreviewText().
  void previewReamToDepth(double depthMm);
  void askPreviewReamToDepth();
  const QString& lastPreviewText() const { return lastPreviewText_; }
  // How fast Replay a recorded path goes against the recorded pace (Reamer → Replay speed: ¼× to 8×; 1 as recorded).
  void setReplaySpeed(double speed);
  double replaySpeed() const { return replaySpeed_; }
  void showPluginsDialog();
  void showError(const QString& title, const QString& message);
  // CT import (MainWindowCtImport.cpp): the plugin's dialog for `path` (empty: the user picks one in
  // it), non-modal; nullptr without the plugin. The result is placed by placeImportedVolume.
  QDialog* importVolume(const QString& path = {});
  // Replaces the bone (undoable) or adds it beside the current one (undoable; shown, not cut).
  void placeImportedVolume(VolumeImportResult result);
  void removeOtherBones();  // undoable
  // Cuts a bone beside instead, and puts the cut bone beside it (undoable, SwapBoneBesideCommand): the
  // `index`-th of the bones beside, or with -1 the only one, or the one the user picks from a list when
  // there are several. False when nothing was swapped (no such bone, or the user cancelled the list).
  bool cutBoneBesideInstead(int index = -1);
  void showBoneInfo();
  // Crash recovery (MainWindowRecovery.cpp, RecoveryFiles.h): while there are unsaved changes, a copy of
  // the bone and its cut log is kept in `dir`, rewritten `delayMs` after the last change; a copy left by a
  // session that did not end normally is offered at once (Restore / Discard). On in a user's window (the
  // folder in the app's data location); tests turn it on with a folder of their own.
  void enableRecovery(const QString& dir, int delayMs);
  const RecoveryFiles* recovery() const { return recovery_.get(); }
  bool recoveryWriteRunning() const { return recoveryWrite_.isRunning(); }
  // Where a restored bone's cut log was kept when it could not be read back into the log panel.
  const QString& recoveredLogPath() const { return recoveredLogPath_; }

 public:
  QString boneFrameText() const;  // the status bar's patient frame and source of the bone
  // What a save of a bone with `facts` to `path` has no room to record (a binary STL's header), as the status bar
  // adds it after "Saved …"; empty when the file keeps all of it.
  static QString factsLeftOut(const QString& path, const BoneFileFacts& facts);
  const OtherBonesLayer* otherBones() const { return otherBones_.get(); }

 protected:
  void closeEvent(QCloseEvent* e) override;  // asks before unsaved changes are lost (confirmDiscardChanges)
  void dragEnterEvent(QDragEnterEvent* e) override;
  void dropEvent(QDropEvent* e) override;

 private:
  void buildActions();
  void buildMenus();
  void buildDocks();
  void buildStatusBar();
  void installBone(ImportedBone bone, const QString& name, const QString& recentPath);
  // Before the bone is closed or replaced by the user (quit, open, recent, drop, default case): with unsaved
  // changes, asks Save / Discard / Cancel; true to go on. A running step is stopped first. Programmatic
  // calls (openFile, loadDefaultCase: tests, demo) do not ask.
  bool confirmDiscardChanges(const QString& action);
  // The question on close about bonesBesideWithUnsavedCuts.
  bool confirmDiscardBonesBeside(const QString& action);
  bool unsavedOutsideTheCutBone(const BoneHistory& history) const;
  // Bones beside with cuts (or restored from a crash copy) whose state no save wrote.
  std::vector<const BoneNode*> unsavedBonesBeside() const;
  // Bones a CT import replaced whose cuts no save wrote: held by the undo history (ReplaceBoneCommand::held).
  std::vector<const BoneContent*> unsavedReplacedBones() const;
  // Its bones beside, as readRecoveryCopy read them (taken from `bones`).
  void restoreBonesBeside(const RecoveredBone& copy, std::vector<RecoveredRead::Beside>& bones);
  RecoveredRead readRecoveryCopyInteractive(const RecoveredBone& copy);  // on a worker, with progress and Cancel
  void removeRecoveryCopy();
  void restoreRecoveredReamer(const RecoveredBone& copy);
  void restoreRecoveredLandmarks(const RecoveredBone& copy);
  // writeTextFile, its error as the message to show (empty when written).
  static QString writeTextReporting(const QString& file, const std::string& text);
  static QString landmarksPathBeside(const QString& bonePath);  // NAME.ply.landmarks.json beside NAME.ply
  void openLandmarksBeside(const QString& bonePath);
  QString keepInRestored(const QString& file) const;  // a copy in recovery/restored/ named <time>_<name>
  bool saveBoneAndCutLogInteractive();  // File → Save bone as… and "Save" in that question: asks where, saveBoneAs
  // The bone's mesh (with `facts` in its comments) and, when given, the states of its undo history beside it
  // (SavedHistory.h), on a worker with a progress dialog (Cancel: the files there unchanged); errors in a dialog;
  // does not mark it saved. True when written.
  bool writeBoneFile(const QString& path, const BoneFileFacts& facts, const std::vector<BoneHistory::Entry>& history = {});
  static QString cutLogPathBeside(const QString& bonePath);  // NAME.ply.cut_log.csv beside NAME.ply
  static QString earlierCutLogPathBeside(const QString& bonePath);  // NAME.cut_log.csv (saves before session 57)
  // A bone opened from a file brings the cut log saved beside it (MainWindowFiles.cpp).
  // `saved`: the facts the bone's file holds (none in a file no save by ReamSim wrote). Returns what the status
  // bar adds to "Opened …".
  QString openCutLogBeside(const QString& bonePath, const BoneFileFacts& saved, const AdoptedHistory& history = {});
  // The undo history read beside an opened bone (ImportOutcome::history) becomes its history, with its steps on
  // the undo stack and the stack at the state the save left; a history that could not be read is named in a
  // dialog and the bone opens without it.
  AdoptedHistory adoptSavedHistory(ImportOutcome& out, const BoneFileFacts& saved, const QString& bonePath);
  // One undo step for each state after the first of the bone's history just adopted (a crash's or a save's),
  // named "<label> (<when>): <volume> mm³, <faces> faces". The stack then stands at the history's last state.
  void stackAdoptedSteps(const QString& when);
  // A file of the user's beside the bone that a save would replace or remove but that could not be read when the
  // bone was opened (`file` is `refused`, and still there): moved aside to NAME.unreadable (.2, .3, … when taken)
  // instead, and `refused` cleared. Throws std::runtime_error.
  static void moveAsideIfRefused(const QString& file, QString& refused);
  // "the file stays as it is (a save moves it aside to NAME.unreadable)": what the refusal's message says of it.
  static QString keptAsideNote(const QString& file);
  void importFinished();
  void showImportProgress(double fraction, const QString& stage);
  void updateStatus();
  void updateTitle();
  void addRecent(const QString& path);
  void rebuildRecentMenu();
  void loadKeyBindings();
  void editKeyBindings();
  void editRenderSettings();
  void askReamToDepth();
  bool waitingForClearPlacement();  // true (and said) while Aim's placement searches: moves and feeds wait
  void askFeedBy();
  bool takeReamer(const ReamerSpec& spec, const QString& description);
  ReamerSpec planReamer(const std::string& reamer, const QString& planFile) const;
  void contactSearched(const ContactSearch& result);
  Pose targetPose() const;
  void buildVolumeImport();  // menu actions, status label, other bones (MainWindowCtImport.cpp)
  void updateBoneFrame();
  void offerRecovery();
  void writeRecoveryCopy();  // or removes the copy when nothing is unsaved
  void endRecovery();        // a normal close: no copy is left behind

  const PluginHost& plugins_;
  const bool persistent_;
  std::unique_ptr<ReamSession> session_;  // outlives every view and panel (see ~MainWindow)
  BoneView* view_ = nullptr;
  std::vector<QDockWidget*> panels_;
  QDockWidget* historyDock_ = nullptr;
  QMap<int, QAction*> moveActions_;
  QMenu* recentMenu_ = nullptr;
  QMenu* viewMenuForDocks_ = nullptr;
  QStringList recent_;
  QDoubleSpinBox* moveStep_ = nullptr;
  QDoubleSpinBox* rotateStep_ = nullptr;
  QDoubleSpinBox* feedStep_ = nullptr;
  QLabel* alertLabel_ = nullptr;
  QLabel* distanceLabel_ = nullptr;
  QLabel* engineLabel_ = nullptr;
  QProgressBar* progress_ = nullptr;
  bool sequenceShown_ = false;  // the progress bar shows a step sequence (a step's own progress waits)
  Subscription alertSubscription_;
  QFutureWatcher<ImportOutcome> importWatcher_;
  QProgressBar* importBusy_ = nullptr;
  QPushButton* importCancel_ = nullptr;
  bool importCancelled_ = false;
  std::shared_ptr<std::atomic<bool>> importStop_;  // read by the import's worker at each progress check
  QString importStoppedAt_;
  bool saving_ = false;  // writeBoneFile is waiting for its worker
  std::set<std::uint64_t> savedRevisions_;  // bone revisions a save wrote (revisions are never reused)
  // First revisions of the bones restored from a crash copy (the cut bone and those beside): unsaved until a
  // save writes them, wherever a swap moves them.
  std::set<std::uint64_t> recoveredRevisions_;
  QString savedPath_;    // where saveBoneAs last wrote the bone (cleared for another bone)
  std::uint64_t boneGeneration_ = 0;  // counts bones installed or replaced: a save knows if its bone is still there
  static constexpr double kContactSearchMm = 100;
  static constexpr int kRecoveryDelayMs = 3000;  // after the last change (a feed's steps write one copy)
  static constexpr std::size_t kMaxQueuedFeedSteps = 4;  // feed key presses beyond this are ignored
  struct PendingDepth {
    Pose start;
    double depthMm;
  };
  std::optional<PendingDepth> pendingDepth_;  // a "ream to depth" waiting for its contact search
  double lastApproachMm_ = -1;
  QString importPath_;
  QString boneName_;
  QString lastError_;
  // CT import (MainWindowCtImport.cpp)
  std::unique_ptr<OtherBonesLayer> otherBones_;
  QLabel* frameLabel_ = nullptr;
  Subscription boneFrameSubscription_;
  // Crash recovery (MainWindowRecovery.cpp)
  std::unique_ptr<RecoveryFiles> recovery_;
  std::unique_ptr<HistoryJournalWriter> journal_;  // the cut bone's undo history in the copy (the writer's alone)
  Subscription landmarksSubscription_;  // a change of the bone's landmarks schedules a copy
  Subscription landmarksTitleSubscription_;  // ... and marks the title
  BonePlanning savedPlanning_;   // the cut bone's landmarks and planned axis as opened or last saved (NAME.landmarks.json)
  QString unreadablePlanningFile_;  // the landmarks beside the bone that could not be read when it was opened
  QString unreadableCutLogFile_;    // the same for its cut log (or one that is not the log saved with the bone)
  QString unreadableHistoryFile_;   // the same for its undo history
  std::optional<BonePlanning> copiedPlanning_;
  std::optional<std::uint64_t> savedBoneRevision_;  // the cut bone's revision as opened or last saved; none: restored
  // The log's notes (annotations) are saved with it (NAME.ply.cut_log.csv): their count of changes at the last save
  // or open (LogNode::notesRevision), and in the crash-recovery copy kept (copiedNotesRevision_; none: no copy).
  struct SavedNotes {
    NodeId log;
    std::uint64_t revision = 0;
    std::vector<std::string> notes;  // by row, as saved (an edit undone back to them is no change)
  } savedNotes_;
  static SavedNotes notesOf(const LogNode& log);
  double replaySpeed_ = 1.0;
  QString lastPreviewText_;
  void removalPreviewed(const RemovalPreviewAnswer& answer);
  bool previewStillHolds(const RemovalPreviewAnswer& answer) const;
  QActionGroup* replaySpeeds_ = nullptr;
  std::optional<std::uint64_t> copiedNotesRevision_;
  Subscription notesSubscription_;  // a note changed: the title...
  Subscription recoveryNotesSubscription_;  // ... and a crash copy
  QTimer recoveryTimer_;
  struct RecoveryWrite {
    QString error;         // empty when the copy was written whole
    bool written = false;  // the copy was written (perhaps without its undo history: `error` says)
  };
  QFutureWatcher<RecoveryWrite> recoveryWrite_;
  bool recoveryOfferPending_ = false;      // a found copy not yet answered: nothing is written or removed
  QString recoveredLogPath_;
};

}  // namespace reamsim::ui
