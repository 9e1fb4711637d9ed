#pragma once
// The live reaming loop of the GUI over the one shared Document.
//
// A reamer move sets the pose in the document at once (the view follows in the same frame) and queues a
// step for the worker. The worker (QtConcurrent, one job at a time) runs the collision query and the
// Boolean on the session's ReamEngine; the result is committed to the Document on the UI thread
// (commitReamStep) and pushed on the undo stack. User moves are coalesced (the latest pose wins while a
// step is running); explicit step sequences (feed, ream to depth, the demo plan) run every step.
// A result computed against a bone that changed meanwhile (undo, new bone) is dropped.
#include <QElapsedTimer>
#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <QTimer>
#include <QUndoStack>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <unordered_map>

#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/InteractionNode.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/PlanNode.h"
#include "reamsim/core/ReamerNode.h"
#include "reamsim/ream/ClearPlacement.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamEngine.h"
#include "reamsim/ream/RemovalPreview.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

class PluginHost;

// The answer to ReamSession::searchContactAlongAxis.
struct ContactSearch {
  enum class Outcome {
    Found,        // approachMm: how far the reamer advances before it first touches the bone (0: touching)
    NoneInReach,  // nothing met within the search's reach
    Dropped,      // not answered: the bone or the reamer changed, or the queue was cleared (a move by hand, Stop, undo)
    Failed,       // the query threw: error
  };
  Outcome outcome = Outcome::Dropped;
  double approachMm = 0;
  QString error;
};

struct StepResult {
  std::optional<double> searchMm;  // a contact search along the axis (no step): how far it looked
  std::optional<double> approachMm;  // its answer
  std::uint64_t engineGeneration = 0;  // of the engine that answered (another reamer: a new engine)
  ReamComputation computation;
  QString error;           // the engine threw: nothing was computed
  bool cancelled = false;  // stopped between the Booleans of a swept turn: nothing was computed
  std::uint64_t revision = 0;  // the bone revision the step started from
  double computeMs = 0;
  std::optional<ClearPlacement> clear;  // a placeClearOfBone's search (NoRoom: nothing was computed)
};

// The answer to ReamSession::previewReamToDepth.
struct RemovalPreviewAnswer {
  enum class Outcome {
    Computed,   // preview: what the steps would remove from the bone as it was asked on
    Stale,      // computed, but the bone changed meanwhile (a cut, an undo): not what it is now
    Cancelled,  // stopped (cancelPreview: Stop, a new bone)
    Failed,     // error says why (no cutting engine, a Boolean that failed)
  };
  Outcome outcome = Outcome::Failed;
  RemovalPreview preview;  // its `after` is not kept: the answer would hold a whole bone
  // What it was asked for: the reamer's pose and the feed step, on the bone's revision with the session's engine
  // generation (another reamer counts one up). The window checks them again before it reams (*Ream it*).
  Pose start;
  double depthMm = 0, stepMm = 0;
  std::uint64_t revision = 0, generation = 0;
  QString error;
};

class ReamSession : public QObject {
  Q_OBJECT
 public:
  explicit ReamSession(const PluginHost& plugins, QObject* parent = nullptr);
  ~ReamSession() override;

  Document& document() { return document_; }
  BoneNode* bone() const { return bone_; }
  ReamerNode* reamer() const { return reamer_; }
  LogNode* log() const { return log_; }
  AlertNode* alerts() const { return alerts_; }
  PlanNode* plan() const { return plan_; }
  // What the next click on the bone in the view does (a landmark being placed).
  InteractionNode* interaction() const { return interaction_; }
  QUndoStack* undoStack() { return &undo_; }

  // Replaces the bone (and starts a new log and undo history). `start` is where the reamer goes.
  void loadBone(ImportedBone bone, const QString& sourceName, const Pose& start);
  // Exchanges the whole bone (history and cursor included) and its cuttability with `other`: the
  // undoable replace of the CT import (BoneCommands.h); calling it twice restores the bone exactly.
  // Unlike loadBone, the undo stack and the log are kept. Defined in BoneExchange.cpp.
  void exchangeBone(BoneContent& other);
  // The bone's history becomes `history` (a crash copy's or a save's, read back), the rest of the bone staying; as
  // exchangeBone for the engine and the log's reference volume (the history's first state). Defined in
  // BoneExchange.cpp.
  void adoptHistory(BoneHistory history);
  // Where the reamer is as far as the bone knows: the pose of the last step computed on it (not a move still
  // waiting or running); none when no step has been computed on it. With returnReamerTo, what a bone exchange
  // keeps for its undo.
  std::optional<Pose> settledReamerPose() const;
  // Puts the reamer at `pose`, without a step, as if the bone's last step had been computed there (the next
  // move sweeps from it): for undo and redo of an exchange, whose bone was last computed with the reamer there.
  void returnReamerTo(const Pose& pose);
  // The reamer: a parametric one, or with `spec.meshFile` a closed mesh read from that file (InputError naming
  // the file when it cannot be a cutting solid; the reamer then stays as it was).
  // A step running when it is called finishes with the reamer it started with (and is logged with it); the
  // reamer changes when it has, and the steps waiting and a pending move run with the new one.
  void setReamer(const ReamerSpec& spec);

  bool canCollide() const;
  bool canCut() const;  // a cutting engine is loaded and the bone is a closed solid
  QString cuttingStatus() const;  // why cutting is off, or the engines in use

  // User move: coalesced; cancels a running step sequence. `moved`: the reamer travelled here from where it
  // was (keys, drag), so a sideways translation cuts the volume it swept; false: it was placed here.
  void moveReamer(const Pose& pose, bool moved = false);
  // A placement (as moveReamer's) that cuts nothing: where the reamer would overlap the bone at `pose`, it is
  // placed out along its axis, as near as it is clear (findClearPlacement, on the worker in the step's own job);
  // where nothing within reach is clear it is not moved. Signals placedOutward / notPlacedClearOfBone say so.
  // Aim asks for it (ReamerNode::requestPlacement's clearOfBone). Until it is answered, where the reamer will be
  // is unknown: placingClearOfBone() says so, and the window takes no move or feed that starts from the reamer
  // meanwhile (a few milliseconds).
  void placeClearOfBone(const Pose& pose);
  bool placingClearOfBone() const;
  // Every step runs (feed, ream to depth, plan), each a travel from the one before; with `placeFirst` the first is
  // placed instead (nothing swept to it), as the command line's plan runner places a plan's first pose.
  void runSteps(const std::vector<Pose>& poses, bool placeFirst = false);
  // The same with each step's placement given (`placed[i]`: nothing swept to poses[i]; a plan's `placed` poses).
  void runSteps(const std::vector<Pose>& poses, const std::vector<bool>& placed);
  // A plan's steps (ReamPlan::expandedPoses) with their placements and notes: a step's note goes to the log row
  // it makes and is announced (noteReached). With a `paceSpeed` (> 0) a pose with a time (t_ms) waits until its
  // time, divided by the speed, has passed since the plan's first timed pose ran: at 1 as it was recorded, at 2
  // twice as fast (a step that takes longer to compute delays the ones after it). Without one (0), and for
  // poses without a time, the steps run as fast as they compute.
  void runPlan(const ReamPlan& plan, double paceSpeed = 0);
  // Queues a search for the first contact of the reamer advancing from `start` along its axis (up to
  // maxMm): run on the worker after the steps queued before it, against the bone they leave, on the
  // engine's own collision structure (no tree is built for it). Answered by contactSearched.
  void searchContactAlongAxis(const Pose& start, double maxMm);
  // What "ream to depth" from `start` (reamToDepthPoses: to the first contact along its axis, then feed steps
  // of stepMm down to depthMm below it) would remove, computed on a copy of the bone by an engine of its own on
  // another worker: the document, the session's engine and its steps are untouched, and the user may go on
  // meanwhile. Answered by removalPreviewed; Stale when the bone or the reamer changed meanwhile. It runs on a
  // thread of its own (previewPool_), so the session's steps never wait behind it. Asked again while one runs,
  // that one is stopped and only the new one answers.
  void previewReamToDepth(const Pose& start, double depthMm, double stepMm);
  void cancelPreview();  // the running preview stops at its next Boolean and answers Cancelled
  static constexpr double kPreviewReachMm = 100;  // how far along its axis a preview looks for the first contact
  std::uint64_t engineGeneration() const { return engineGeneration_; }
  // Drops the queued steps and stops the running one between two of its Booleans (a long swing is a chain
  // of them): a stopped step leaves the bone as it was and the reamer where that step started.
  void cancelQueued();
  std::size_t queuedSteps() const { return queued_.size(); }
  // Show first, compute next: with the gate on, a move by hand starts its step once the view has presented
  // the moved reamer (frameShown), or after kFrameGateMs at the latest, so that the step's computation does
  // not compete with drawing that frame for the cores.
  void setFrameGate(bool on) { frameGate_ = on; }
  void frameShown();
  bool lastStepSwept() const { return lastStepSwept_; }  // the last committed step cut a swept volume
  bool busy() const;
  Pose targetPose() const;  // where the reamer is once every requested step has run
  // Processes events until no step is running or queued; false on timeout (tests, demo, benchmark).
  bool waitIdle(int timeoutMs);

  // The reamer's path on this bone: every step committed since the bone was opened (a cut or not), in order,
  // each a move from the one before or a placement. Replayed on the bone as opened (a plan with these poses
  // and placements, MainWindow::exportPath) it makes the same cuts, unless steps were undone in between
  // or the bone was exchanged in between (pathInterrupted) or the reamer changed (each step names its own).
  struct PathStep {
    Pose pose;
    bool placed = false;
    ReamerSpec reamer;
    std::size_t stepIndex = 0;   // the step's number (CutLogEntry::stepIndex of its log row, if it made one)
    std::int64_t timeUnixMs = 0;  // when it was committed
  };
  const std::vector<PathStep>& path() const { return path_; }
  // The bone changed under the path other than by its own steps: an undo, a redo, a bone exchanged.
  bool pathInterrupted() const { return pathInterrupted_; }
  // Where the path starts: the bone as opened, as restored from a crash copy, or as an undo or redo before
  // its first step left it. The path starts again from the bone as it is now with restartPath (loadBone does
  // this; a crash restore, once it has put the recovered history back).
  enum class PathStart { AsOpened, AsRecovered, Changed };  // Changed: by an undo, a redo or an exchange
  PathStart pathStart() const { return pathStart_; }
  void restartPath(PathStart start = PathStart::AsOpened);

  // Edits of the bone's landmarks and planned axis (whoever makes them: the Planning dock, a click in the view)
  // go on the undo stack as they reach the document (PlanningCommand). Landmarks that come with a bone are not
  // edits: loadBone, exchangeBone and adoptHistory are quiet, and so is whatever runs while a QuietPlanning
  // lives (the window applying the landmarks saved beside a bone it opens, or a crash copy's).
  class QuietPlanning {
   public:
    explicit QuietPlanning(ReamSession& session) : session_(session) { ++session_.planningQuiet_; }
    ~QuietPlanning();
    QuietPlanning(const QuietPlanning&) = delete;
    QuietPlanning& operator=(const QuietPlanning&) = delete;

   private:
    ReamSession& session_;
  };
  // Puts `planning` on the bone for an undo or redo of a PlanningCommand (not itself an edit), when the bone's
  // planning is still `expected` (what the command left): an edit made since that the stack could not record
  // (editNotRecorded) is left as it is, with a message, rather than silently taken back.
  void restorePlanning(const BonePlanning& planning, const BonePlanning& expected);
  // Puts `note` on row `row` of the log `log` (when it is still the session's) for an undo or redo of a
  // NoteCommand (not itself an edit), when the row's note is still `expected`, as for the planning. Notes written
  // on the log's rows go on the undo stack as they reach the document, as landmark edits do.
  void restoreNote(NodeId log, std::size_t row, const std::string& note, const std::string& expected);

  std::size_t cutsCommitted() const { return cuts_; }
  double lastMinDistanceMm() const { return lastMinDistance_; }
  // The bone's volume before its first logged cut (the log's cumulative volume is measured against it).
  double initialVolumeMm3() const { return initialVolume_ + removedBeforeMm3(); }

  // After loadBone of a bone restored from a crash-recovery copy: the log the crashed session kept, so that
  // the log panel lists it, new steps continue its numbering and the cumulative volume goes on from what had
  // been removed from this bone (`removedMm3`, as the copy recorded it: cuts undone before the crash are not
  // counted; without it, the last row's cumulative volume). The rows' bone revisions belong to the crashed
  // session's history: those `revisions` maps (the crashed history's to the adopted one's, state by state)
  // become this history's, the others are cleared (0).
  void continueLog(std::vector<CutLogEntry> earlier, std::optional<double> removedMm3 = std::nullopt,
                   const std::unordered_map<std::uint64_t, std::uint64_t>& revisions = {});

 Q_SIGNALS:
  void busyChanged(bool busy);
  void progress(int done, int total);  // of the current step sequence
  void stepFinished(double minDistanceMm, bool contact);
  void engineError(const QString& message);
  void stepCancelled();  // the running step was stopped (cancelQueued): the bone is unchanged
  // How far the running step has got when it is a chain of Booleans (a swept turn), every kProgressMs.
  void stepProgress(int booleansDone, int booleansTotal);
  void boneReplaced();
  void contactSearched(const ContactSearch& result);
  void noteReached(const QString& note);  // a plan's step with a note was committed
  void placedOutward(double retreatMm);   // placeClearOfBone: placed this far out along the axis than asked
  // placeClearOfBone placed nothing, the reamer back where it was: nothing clear within reach (or `unchecked`:
  // the contact engine cannot tell, ReamEngine::overlapsAt), or `dropped`: stopped, failed, or the bone changed
  // meanwhile (an undo).
  void notPlacedClearOfBone(bool unchecked, bool dropped);
  void removalPreviewed(const RemovalPreviewAnswer& answer);
  // A landmark edit or a note was made while undone cuts or bones could be redone: it is not on the undo stack.
  // `message` says so, for the status bar.
  void editNotRecorded(const QString& message);

 private:
  void startNext();
  void finished();
  void rebuildEngine();
  void clearQueue();  // drops the queued steps; a queued contact search is answered Dropped
  void queuePendingUserMove();  // the move by hand not yet computed goes to the queue's end
  void startSearch(const Pose& start, double maxMm);
  // Runs `job` on the worker against the current bone, timed; an exception becomes the result's error
  // (ReamCancelled: cancelled). One job at a time: the engine is not shared between threads.
  using WorkerJob = std::function<void(ReamEngine&, const BoneState&, std::uint64_t revision, StepResult&)>;
  void runOnWorker(WorkerJob job);
  void answerSearch(const StepResult& r);

  const PluginHost& plugins_;
  Document document_;
  BoneNode* bone_ = nullptr;
  ReamerNode* reamer_ = nullptr;
  LogNode* log_ = nullptr;
  AlertNode* alerts_ = nullptr;
  PlanNode* plan_ = nullptr;
  InteractionNode* interaction_ = nullptr;
  Subscription placementRequests_;  // a panel or device asking for the reamer somewhere: placed there
  Subscription planningEdits_;      // the bone's landmarks or planned axis changed: an edit to record?
  void recordPlanningEdit();
  BonePlanning recordedPlanning_;   // the planning the undo stack knows the bone has
  int planningQuiet_ = 0;
  // A PlanningCommand's or NoteCommand's undo or redo: the bone itself did not change.
  bool annotationCommandRan_ = false;
  // Whether an edit of the landmarks or a note may go on the stack: a push drops what could be redone, which
  // may be other such edits but not undone cuts or bones (the bone's history would keep states the stack no
  // longer reaches, and an undone CT import would be lost).
  bool redoHoldsOnlyAnnotations() const;
  Subscription noteEdits_;                // the log changed: a note written to record?
  std::vector<std::string> recordedNotes_;  // the notes the undo stack knows the log's rows have
  void watchLog();                        // after the log node is made: follows its notes
  void recordNoteEdits();
  QUndoStack undo_;
  bool pushingOwnCommand_ = false;
  double initialVolume_ = 0;

  std::unique_ptr<ReamEngine> engine_;
  std::uint64_t engineGeneration_ = 0;  // counts rebuildEngine calls
  QFutureWatcher<StepResult> watcher_;
  QFutureWatcher<RemovalPreviewAnswer> previewWatcher_;
  std::shared_ptr<StepControl> previewControl_;
  QThreadPool previewPool_;  // one thread: a preview never takes the steps' or the saves' threads
  bool running_ = false;
  void takeReamer(const ReamerSpec& spec, std::shared_ptr<const TriangleMesh> cuttingVolume);
  struct PendingReamer {
    ReamerSpec spec;
    std::shared_ptr<const TriangleMesh> cuttingVolume;
  };
  std::optional<PendingReamer> pendingReamer_;  // chosen while a step ran: taken when it has finished
  struct QueuedStep {
    Pose pose;
    std::optional<double> searchMm;  // set: a contact search from `pose` along its axis, not a step
    bool placed = false;             // placed there (nothing swept), not a travel from the step before
    std::string note;                // a plan's note for the step
    std::optional<double> dueMs;     // paced: not started before paceClock_ has reached it
    bool clearOfBone = false;        // a placement that cuts nothing (placeClearOfBone)
  };
  // A sequence's steps to the queue's end (after the pending move by hand), counted for progress, and started.
  void queueSequence(std::vector<QueuedStep> steps);
  QElapsedTimer paceClock_;  // started when a paced plan is queued
  QTimer* paceTimer_ = nullptr;  // wakes the queue when the next paced step is due
  std::string runningNote_;
  std::deque<QueuedStep> queued_;
  std::vector<PathStep> path_;
  std::optional<PathStep> runningStep_;  // what the running step adds to the path once committed
  bool pathInterrupted_ = false;
  PathStart pathStart_ = PathStart::AsOpened;
  std::uint64_t pathRevision_ = 0;  // the cut bone's revision where the path stands (after its last step)
  std::optional<Pose> latestUserPose_;
  bool latestUserMoved_ = false;
  bool latestUserClear_ = false;  // the pending move by hand is a placeClearOfBone
  bool runningClear_ = false;     // the running step is one
  Pose poseBeforeClear_;          // where the reamer was shown before placeClearOfBone (put back when no pose was
                                  // computed yet, e.g. the first move after a load)
  void moveReamerAs(const Pose& pose, bool moved, bool clearOfBone);
  bool lastStepSwept_ = false;
  bool frameGate_ = false, waitingForFrame_ = false;
  static constexpr int kFrameGateMs = 50;  // every coalesced move since the last step was a travel (see moveReamer)
  std::optional<Pose> lastComputedPose_;
  std::optional<Pose> poseBeforeRunning_;             // lastComputedPose_ before the running step
  std::shared_ptr<StepControl> control_;              // of the running step: Stop raises it, progress reads it
  QTimer* progressTimer_ = nullptr;
  static constexpr int kProgressMs = 100;
  int sequenceDone_ = 0, sequenceTotal_ = 0;
  std::size_t cuts_ = 0, steps_ = 0;
  // Removed from a bone before its history here began (a restored log), by the history's first revision: a
  // CT import that replaces the bone (exchangeBone) swaps histories, and the other bone starts from its own.
  std::unordered_map<std::uint64_t, double> removedBefore_;
  double removedBeforeMm3() const;
  double lastMinDistance_ = std::numeric_limits<double>::infinity();
};

}  // namespace reamsim::ui

// Carried in QVariant by QSignalSpy (tests) and queued connections.
Q_DECLARE_METATYPE(reamsim::ui::RemovalPreviewAnswer)
