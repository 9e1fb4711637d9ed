#include "ReamSession.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <QElapsedTimer>
#include <QEventLoop>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>

#include "CutCommand.h"
#include "NoteCommand.h"
#include "PlanningCommand.h"
#include "PluginHost.h"
#include "reamsim/ream/ReamStep.h"
#include "reamsim/tools/ReamerFile.h"

namespace reamsim::ui {

ReamSession::ReamSession(const PluginHost& plugins, QObject* parent) : QObject(parent), plugins_(plugins) {
  qRegisterMetaType<RemovalPreviewAnswer>();
  qRegisterMetaType<RemovalPreviewAnswer>("RemovalPreviewAnswer");  // as the signal names it
  bone_ = &document_.create<BoneNode>("Bone");
  reamer_ = &document_.create<ReamerNode>("Reamer");
  plan_ = &document_.create<PlanNode>("Plan");
  log_ = &document_.create<LogNode>("Log");
  alerts_ = &document_.create<AlertNode>("Alerts");
  interaction_ = &document_.create<InteractionNode>("Interaction");
  placementRequests_ = document_.observeNode(reamer_->id(), [this] {
    if (const auto request = reamer_->takePlacementRequest())
      request->clearOfBone ? placeClearOfBone(request->pose) : moveReamer(request->pose, false);
  });
  planningEdits_ = document_.observeNode(bone_->id(), [this] { recordPlanningEdit(); });
  watchLog();
  undo_.setUndoLimit(0);  // unlimited: the states share storage (see CutCommand)
  // Undo or redo (menu, keys, history view) stops a queued sequence: its remaining steps were planned on
  // the bone being left, and the step in flight is dropped (computed against the old bone).
  connect(&undo_, &QUndoStack::indexChanged, this, [this] {
    if (pushingOwnCommand_) return;
    // Only landmark edits or notes undone or redone (a jump in the History dock may pass cuts too): the bone is as
    // it was, and so are the path and the steps queued on it.
    if (std::exchange(annotationCommandRan_, false) && bone_->currentRevision() == pathRevision_) return;
    // The path goes on from a bone its steps did not leave (an undo, a redo, an exchanged bone; not a bone added
    // beside). Before its first step it simply starts from there.
    if (bone_->currentRevision() != pathRevision_) {
      if (path_.empty())
        pathStart_ = PathStart::Changed;
      else
        pathInterrupted_ = true;
      pathRevision_ = bone_->currentRevision();
    }
    if (!queued_.empty() || running_) cancelQueued();
  });
  connect(&watcher_, &QFutureWatcher<StepResult>::finished, this, &ReamSession::finished);
  previewPool_.setMaxThreadCount(1);
  connect(&previewWatcher_, &QFutureWatcher<RemovalPreviewAnswer>::finished, this, [this] {
    RemovalPreviewAnswer answer = previewWatcher_.result();
    if (answer.outcome == RemovalPreviewAnswer::Outcome::Computed &&
        (answer.revision != bone_->currentRevision() || answer.generation != engineGeneration_))
      answer.outcome = RemovalPreviewAnswer::Outcome::Stale;
    Q_EMIT removalPreviewed(answer);
  });
  paceTimer_ = new QTimer(this);
  paceTimer_->setSingleShot(true);
  connect(paceTimer_, &QTimer::timeout, this, [this] { startNext(); });
  progressTimer_ = new QTimer(this);
  progressTimer_->setInterval(kProgressMs);
  connect(progressTimer_, &QTimer::timeout, this, [this] {
    if (!control_) return;
    const int total = control_->booleansTotal.load();
    if (total > 1) Q_EMIT stepProgress(control_->booleansDone.load(), total);
  });
}

ReamSession::~ReamSession() {
  // ~QUndoStack clears the stack and reports indexChanged, after the members declared behind it are gone: this
  // session must not hear it.
  undo_.disconnect(this);
  queued_.clear();  // nobody to answer
  latestUserPose_.reset();
  if (control_) control_->stop = true;  // a long swing stops at its next Boolean
  if (running_) watcher_.waitForFinished();  // the job uses engine_
  watcher_.disconnect(this);
  if (previewControl_) previewControl_->stop = true;
  previewWatcher_.disconnect(this);
  previewPool_.waitForDone();  // it reads the plugins (a stopped preview ends at its next check)
}

void ReamSession::loadBone(ImportedBone b, const QString& sourceName, const Pose& start) {
  const QuietPlanning quiet(*this);  // the new bone comes without landmarks: not an edit
  cancelQueued();
  cancelPreview();  // asked of the bone that goes
  if (running_) watcher_.waitForFinished();  // its result is dropped: the revision changes below
  {
    Document::BatchScope batch(document_);
    bone_->setName(sourceName.toStdString());
    bone_->resetHistory(BoneState::fromMesh(b.mesh), "import");
    bone_->setOriginalMesh(std::move(b.original));
    bone_->setImportReport(std::move(b.report));
    bone_->setCuttable(b.cuttable);
    document_.remove(log_->id());  // the log is append-only: a new bone gets a new one
    log_ = &document_.create<LogNode>("Log");
    watchLog();
    alerts_->clear();
    bone_->setLandmarks({});  // another bone: the points and the plan were on the one before
    bone_->setPlannedAxis(std::nullopt);
    interaction_->setPlaceRequest(std::nullopt);
    reamer_->setPose(start);
  }
  undo_.clear();
  restartPath();
  initialVolume_ = bone_->current().volume();
  cuts_ = steps_ = 0;
  removedBefore_.clear();
  lastComputedPose_.reset();
  lastMinDistance_ = std::numeric_limits<double>::infinity();
  rebuildEngine();
  Q_EMIT boneReplaced();
}

void ReamSession::restartPath(PathStart start) {
  path_.clear();
  pathInterrupted_ = false;
  pathStart_ = start;
  pathRevision_ = bone_->currentRevision();
}

void ReamSession::continueLog(std::vector<CutLogEntry> earlier, std::optional<double> removedMm3,
                              const std::unordered_map<std::uint64_t, std::uint64_t>& revisions) {
  if (earlier.empty()) return;
  Document::BatchScope batch(document_);
  for (CutLogEntry& e : earlier) {
    const auto mapped = revisions.find(e.boneStateId);
    e.boneStateId = mapped == revisions.end() ? 0 : mapped->second;
    steps_ = std::max(steps_, e.stepIndex + 1);
    log_->append(std::move(e));
  }
  removedBefore_[bone_->history().entries().front().revision] = removedMm3.value_or(log_->cumulativeMm3());
}

ReamSession::QuietPlanning::~QuietPlanning() {
  // Whatever changed meanwhile is where the undo stack now starts from, also when its report comes later (a
  // batch still open around this scope).
  if (--session_.planningQuiet_ == 0) session_.recordedPlanning_ = planningOf(*session_.bone_);
}

void ReamSession::recordPlanningEdit() {
  const BonePlanning now = planningOf(*bone_);
  if (now == recordedPlanning_) return;  // a cut, a name, a frame: not the planning
  BonePlanning before = std::exchange(recordedPlanning_, now);
  if (planningQuiet_ > 0) return;
  if (!redoHoldsOnlyAnnotations()) {  // made, but not recorded
    Q_EMIT editNotRecorded(tr("The landmark edit is made but Undo cannot take it back: recording it would drop the "
                              "undone steps that Redo can still bring back"));
    return;
  }
  pushingOwnCommand_ = true;  // our own push is not an undo
  undo_.push(new PlanningCommand(*this, std::move(before), now));
  pushingOwnCommand_ = false;
}

namespace {
// A landmark edit, a note, or a macro of them (notes written on several rows at once).
bool isAnnotation(const QUndoCommand* c) {
  if (dynamic_cast<const PlanningCommand*>(c) || dynamic_cast<const NoteCommand*>(c)) return true;
  if (c->childCount() == 0) return false;
  for (int i = 0; i < c->childCount(); ++i)
    if (!isAnnotation(c->child(i))) return false;
  return true;
}
}  // namespace

bool ReamSession::redoHoldsOnlyAnnotations() const {
  for (int i = undo_.index(); i < undo_.count(); ++i)
    if (!isAnnotation(undo_.command(i))) return false;
  return true;
}

void ReamSession::restorePlanning(const BonePlanning& planning, const BonePlanning& expected) {
  annotationCommandRan_ = true;  // the stack reports the index change once undo() or redo() has returned
  const BonePlanning now = planningOf(*bone_);
  if (now != expected && now != planning) {
    Q_EMIT editNotRecorded(tr("The landmarks were changed since by an edit Undo could not record: they are left as "
                              "they are"));
    return;
  }
  const QuietPlanning quiet(*this);
  applyPlanning(*bone_, planning);
}

void ReamSession::watchLog() {
  recordedNotes_.clear();
  for (const CutLogEntry& e : log_->entries()) recordedNotes_.push_back(e.note);
  noteEdits_ = document_.observeNode(log_->id(), [this] { recordNoteEdits(); });
}

void ReamSession::recordNoteEdits() {
  struct Edit {
    std::size_t row;
    std::string before;
  };
  std::vector<Edit> edits;
  const std::vector<CutLogEntry>& rows = log_->entries();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i >= recordedNotes_.size())
      recordedNotes_.push_back(rows[i].note);  // a new row: its note (a plan's) came with its step
    else if (rows[i].note != recordedNotes_[i])
      edits.push_back({i, std::exchange(recordedNotes_[i], rows[i].note)});
  }
  if (edits.empty()) return;
  if (!redoHoldsOnlyAnnotations()) {  // made, but not recorded
    Q_EMIT editNotRecorded(tr("The note is made but Undo cannot take it back: recording it would drop the undone "
                              "steps that Redo can still bring back"));
    return;
  }
  pushingOwnCommand_ = true;  // our own push is not an undo
  if (edits.size() > 1) undo_.beginMacro(tr("Notes on %1 steps").arg(edits.size()));  // one change, one undo
  for (Edit& e : edits)
    undo_.push(new NoteCommand(*this, log_->id(), e.row, rows[e.row].stepIndex, std::move(e.before), rows[e.row].note));
  if (edits.size() > 1) undo_.endMacro();
  pushingOwnCommand_ = false;
}

void ReamSession::restoreNote(NodeId log, std::size_t row, const std::string& note, const std::string& expected) {
  if (log != log_->id() || row >= log_->size()) return;  // another bone's log (loadBone clears the stack)
  annotationCommandRan_ = true;
  const std::string& now = log_->entries()[row].note;
  if (now != expected && now != note) {
    Q_EMIT editNotRecorded(tr("The note on step %1 was changed since by an edit Undo could not record: it is left "
                              "as it is").arg(log_->entries()[row].stepIndex));
    return;
  }
  // Known to the stack already: not an edit (rows appended in a batch still open are not in the shadow yet).
  if (recordedNotes_.size() <= row) recordedNotes_.resize(row + 1);
  recordedNotes_[row] = note;
  log_->setNote(row, note);
}

double ReamSession::removedBeforeMm3() const {
  const auto it = removedBefore_.find(bone_->history().entries().front().revision);
  return it == removedBefore_.end() ? 0.0 : it->second;
}

void ReamSession::setReamer(const ReamerSpec& spec) {
  // Read (and checked) first: a file that cannot be a cutting solid leaves the reamer as it was.
  auto volume = std::make_shared<const TriangleMesh>(cuttingSolidFor(spec));
  // Neither stopped nor waited for (a long swing takes seconds): the running step finishes with the engine it
  // started on, and finished() takes the new reamer before the next step starts.
  if (running_) {
    pendingReamer_ = PendingReamer{spec, std::move(volume)};
    return;
  }
  takeReamer(spec, std::move(volume));
}

void ReamSession::takeReamer(const ReamerSpec& spec, std::shared_ptr<const TriangleMesh> cuttingVolume) {
  pendingReamer_.reset();
  reamer_->setSpec(spec);
  reamer_->setCuttingVolume(std::move(cuttingVolume));
  if (!engine_) return rebuildEngine();
  // The engine keeps the bone's tree and the cutter's exact coordinates; answers computed for the reamer before
  // are told apart by the generation, as after a rebuild.
  engine_->setReamer(reamer_->cuttingVolume(), reamer_->spec());
  ++engineGeneration_;
}

void ReamSession::rebuildEngine() {
  engine_.reset();
  ++engineGeneration_;
  if (!reamer_->cuttingVolume() || bone_->current().empty()) return;
  std::unique_ptr<ContactBackend> contact = plugins_.collision() ? plugins_.collision()->createContactBackend() : nullptr;
  CutBackendFactory cut = plugins_.csg() && bone_->cuttable() ? plugins_.csg()->cutBackendFactory() : CutBackendFactory{};
  engine_ = std::make_unique<ReamEngine>(reamer_->cuttingVolume(), std::move(contact), std::move(cut), reamer_->spec());
}

bool ReamSession::canCollide() const { return engine_ && engine_->canCollide(); }
bool ReamSession::canCut() const { return engine_ && engine_->canCollide() && engine_->canCut(); }

QString ReamSession::cuttingStatus() const {
  if (!plugins_.collision()) return tr("no collision plugin: the reamer moves without collision or cutting");
  if (!plugins_.csg()) return tr("no CSG plugin: collision alerts only, no cutting");
  if (!bone_->cuttable()) return tr("the bone is not a closed solid: collision alerts only, no cutting");
  return tr("collision: %1; cutting: %2").arg(plugins_.collision()->engineName(), plugins_.csg()->engineName());
}

void ReamSession::moveReamer(const Pose& pose, bool moved) { moveReamerAs(pose, moved, false); }

void ReamSession::placeClearOfBone(const Pose& pose) {
  if (!placingClearOfBone()) poseBeforeClear_ = reamer_->pose();
  moveReamerAs(pose, false, true);
}

bool ReamSession::placingClearOfBone() const {
  return runningClear_ || (latestUserPose_ && latestUserClear_) ||
         std::any_of(queued_.begin(), queued_.end(), [](const QueuedStep& q) { return q.clearOfBone; });
}

void ReamSession::moveReamerAs(const Pose& pose, bool moved, bool clearOfBone) {
  reamer_->setPose(pose);  // the view follows at once; the step itself is computed on the worker
  if (!engine_) return;
  if (!queued_.empty()) {  // a move by hand interrupts a feed sequence
    clearQueue();
    sequenceDone_ = sequenceTotal_ = 0;
    Q_EMIT progress(0, 0);
  }
  // Coalesced moves sweep from the last computed pose only if every one of them was a travel.
  latestUserMoved_ = (latestUserPose_ ? latestUserMoved_ : true) && moved;
  latestUserPose_ = pose;
  latestUserClear_ = clearOfBone;  // the newest move decides
  if (frameGate_ && !running_) {
    if (!waitingForFrame_) {
      waitingForFrame_ = true;
      QTimer::singleShot(kFrameGateMs, this, [this] { frameShown(); });  // no frame came (hidden view)
    }
    return;
  }
  startNext();
}

void ReamSession::frameShown() {
  if (!waitingForFrame_) return;
  waitingForFrame_ = false;
  startNext();
}

void ReamSession::runSteps(const std::vector<Pose>& poses, bool placeFirst) {
  std::vector<bool> placed(poses.size(), false);
  if (placeFirst && !placed.empty()) placed.front() = true;
  runSteps(poses, placed);
}

void ReamSession::runSteps(const std::vector<Pose>& poses, const std::vector<bool>& placed) {
  if (!engine_ || poses.empty()) return;
  std::vector<QueuedStep> steps;
  for (std::size_t i = 0; i < poses.size(); ++i) steps.push_back({poses[i], std::nullopt, i < placed.size() && placed[i], {}, std::nullopt, false});
  queueSequence(std::move(steps));
}

void ReamSession::queueSequence(std::vector<QueuedStep> steps) {
  queuePendingUserMove();  // keep the order: the pending move by hand first
  sequenceTotal_ += static_cast<int>(steps.size());
  for (QueuedStep& s : steps) queued_.push_back(std::move(s));
  Q_EMIT progress(sequenceDone_, sequenceTotal_);
  startNext();
}

void ReamSession::runPlan(const ReamPlan& plan, double paceSpeed) {
  const std::vector<Pose> poses = plan.expandedPoses();
  if (!engine_ || poses.empty()) return;
  std::vector<bool> placed = plan.expandedPlacements();
  placed.front() = true;  // as the command line's runner: the first pose comes from nowhere
  const std::vector<std::string> notes = plan.expandedNotes();
  const std::vector<std::optional<double>> times = plan.expandedTimesMs();
  std::optional<double> firstTime;
  std::vector<QueuedStep> steps;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    QueuedStep step{poses[i], std::nullopt, placed[i], notes[i], std::nullopt, false};
    if (paceSpeed > 0 && times[i]) {
      if (!firstTime) firstTime = times[i];
      step.dueMs = (*times[i] - *firstTime) / paceSpeed;
    }
    steps.push_back(std::move(step));
  }
  paceClock_.invalidate();  // started by the first paced step (after the steps queued before it)
  queueSequence(std::move(steps));
}

void ReamSession::previewReamToDepth(const Pose& start, double depthMm, double stepMm) {
  RemovalPreviewAnswer asked;  // outcome Failed until computed
  asked.start = start;
  asked.depthMm = depthMm;
  asked.stepMm = stepMm;
  const auto refuse = [&](const QString& why) {
    asked.error = why;
    Q_EMIT removalPreviewed(asked);
  };
  const CollisionInterface* collision = plugins_.collision();
  const CsgInterface* csg = plugins_.csg();
  if (!collision || !csg || !bone_->cuttable() || !reamer_->cuttingVolume() || bone_->current().empty())
    return refuse(tr("Nothing can be cut here: %1").arg(cuttingStatus()));
  if (!(depthMm > 0) || !(stepMm > 0)) return refuse(tr("The depth and the feed step must be positive."));
  // A preview still running is stopped, not waited for: it ends at its next check on the preview's own thread,
  // before this one starts there, and the watcher hears this one only.
  if (previewControl_) previewControl_->stop = true;
  previewControl_ = std::make_shared<StepControl>();
  asked.revision = bone_->currentRevision();
  asked.generation = engineGeneration_;
  previewWatcher_.setFuture(QtConcurrent::run(
      &previewPool_, [collision, cut = csg->cutBackendFactory(), volume = reamer_->cuttingVolume(), spec = reamer_->spec(),
                      bone = bone_->current(), control = previewControl_, asked]() -> RemovalPreviewAnswer {
        RemovalPreviewAnswer a = asked;
        const Pose start = a.start;
        const double depthMm = a.depthMm, stepMm = a.stepMm;
        try {
          if (control->stop) throw ReamCancelled();  // before building an engine for nothing
          ReamEngine engine(volume, collision->createContactBackend(), cut, spec);
          a.preview = reamsim::previewReamToDepth(engine, bone, start, depthMm, stepMm, kPreviewReachMm, control.get());
          if (control->stop) throw ReamCancelled();  // before an O(bone) measure
          try {
            previewSeat(a.preview, spec);  // how much of the face the reamed bone would seat
          } catch (const std::exception&) {  // the preview stands without it (the answer says no seat)
          }
          a.preview.after = BoneState{};  // the future keeps its result until the next preview: not a whole bone
          a.outcome = RemovalPreviewAnswer::Outcome::Computed;
        } catch (const ReamCancelled&) {
          a.outcome = RemovalPreviewAnswer::Outcome::Cancelled;
        } catch (const std::exception& e) {
          a.outcome = RemovalPreviewAnswer::Outcome::Failed;
          a.error = QString::fromStdString(e.what());
        }
        return a;
      }));
}

void ReamSession::cancelPreview() {
  if (previewControl_) previewControl_->stop = true;
}

void ReamSession::queuePendingUserMove() {
  if (!latestUserPose_) return;
  queued_.push_back({*latestUserPose_, std::nullopt, !latestUserMoved_, {}, std::nullopt, latestUserClear_});  // a placement stays one (Aim)
  latestUserPose_.reset();
}

void ReamSession::searchContactAlongAxis(const Pose& start, double maxMm) {
  if (!engine_ || !(maxMm > 0)) {
    ContactSearch r;
    r.outcome = ContactSearch::Outcome::Failed;
    r.error = tr("There is no reamer or no bone to search along.");
    Q_EMIT contactSearched(r);
    return;
  }
  queuePendingUserMove();  // keep the order: the pending move by hand first
  queued_.push_back({start, maxMm, false, {}, std::nullopt, false});
  startNext();
}

void ReamSession::clearQueue() {
  const bool searchQueued =
      std::any_of(queued_.begin(), queued_.end(), [](const QueuedStep& q) { return q.searchMm.has_value(); });
  queued_.clear();
  paceTimer_->stop();
  if (searchQueued) Q_EMIT contactSearched(ContactSearch{});  // Dropped
}

void ReamSession::cancelQueued() {
  if (running_ && control_) control_->stop = true;
  // A clear placement not started yet is shown at the pose asked, in the bone: back where the reamer was.
  const bool clearWaiting = placingClearOfBone() && !runningClear_;
  clearQueue();
  latestUserPose_.reset();
  if (clearWaiting) reamer_->setPose(lastComputedPose_ ? *lastComputedPose_ : poseBeforeClear_);
  waitingForFrame_ = false;
  sequenceDone_ = sequenceTotal_ = 0;
  Q_EMIT progress(0, 0);
  if (!running_) Q_EMIT busyChanged(false);
}

Pose ReamSession::targetPose() const {
  if (latestUserPose_) return *latestUserPose_;
  if (!queued_.empty()) return queued_.back().pose;
  if (running_ && lastComputedPose_) return *lastComputedPose_;
  return reamer_->pose();
}

bool ReamSession::busy() const { return running_ || !queued_.empty() || latestUserPose_.has_value(); }

bool ReamSession::waitIdle(int timeoutMs) {
  if (!busy()) return true;
  QEventLoop loop;
  auto c = connect(this, &ReamSession::busyChanged, &loop, [&](bool b) {
    if (!b) loop.quit();
  });
  QTimer::singleShot(timeoutMs, &loop, &QEventLoop::quit);
  loop.exec();
  disconnect(c);
  return !busy();
}

void ReamSession::startNext() {
  if (running_) return;
  if (!engine_ || (queued_.empty() && !latestUserPose_)) {
    sequenceDone_ = sequenceTotal_ = 0;
    Q_EMIT busyChanged(false);
    return;
  }
  Pose pose;
  bool moved = true;  // queued steps (feeds, ream to depth, plans) follow a path
  bool clearOfBone = false;
  runningNote_.clear();
  if (!queued_.empty()) {
    if (const std::optional<double> due = queued_.front().dueMs) {
      if (!paceClock_.isValid()) paceClock_.start();  // the recorded path's first timed step: its time 0
      const double wait = std::ceil(*due - double(paceClock_.elapsed()));
      if (wait > 0) {  // busy meanwhile (the queue is not empty): a move by hand or Stop drops the rest
        paceTimer_->start(int(std::min(wait, double(std::numeric_limits<int>::max()))));  // longer: asked again
        return;
      }
    }
    const QueuedStep next = queued_.front();
    queued_.pop_front();
    runningNote_ = next.note;
    if (next.searchMm) {
      startSearch(next.pose, *next.searchMm);
      return;
    }
    pose = next.pose;
    moved = !next.placed;
    clearOfBone = next.clearOfBone;
  } else {
    pose = *latestUserPose_;
    moved = latestUserMoved_;
    clearOfBone = latestUserClear_;
    latestUserPose_.reset();
  }
  // A placed step comes from nowhere, as the command line's first pose of a plan (its broad phase looks no wider).
  const double stepMm = moved && lastComputedPose_ ? norm(pose.tip - lastComputedPose_->tip) : 0.0;
  const std::optional<Pose> sweptFrom = moved ? lastComputedPose_ : std::nullopt;
  poseBeforeRunning_ = lastComputedPose_;
  lastComputedPose_ = pose;
  runningStep_ = PathStep{pose, !sweptFrom, reamer_->spec()};
  runningClear_ = clearOfBone;
  control_ = std::make_shared<StepControl>();
  progressTimer_->start();
  runOnWorker([pose, stepMm, sweptFrom, clearOfBone, control = control_](ReamEngine& engine, const BoneState& state,
                                                                         std::uint64_t revision, StepResult& r) {
    Pose at = pose;
    if (clearOfBone) {  // in this job: nothing can change the bone between the search and the step
      r.clear = findClearPlacement(engine, state, revision, pose);
      if (r.clear->outcome == ClearPlacement::Outcome::NoRoom || r.clear->outcome == ClearPlacement::Outcome::Unsupported)
        return;  // nothing is placed
      at = r.clear->pose;
    }
    r.computation = engine.compute(state, revision, at, stepMm, sweptFrom ? &*sweptFrom : nullptr, control.get());
  });
}

// A contact search runs on the worker like a step (one job at a time: the engine's structures are not shared
// between threads) but moves nothing and commits nothing.
void ReamSession::startSearch(const Pose& start, double maxMm) {
  control_.reset();
  runOnWorker([start, maxMm](ReamEngine& engine, const BoneState& state, std::uint64_t revision, StepResult& r) {
    r.searchMm = maxMm;
    r.approachMm = engine.advanceToContactMm(state, revision, start, maxMm);
  });
}

void ReamSession::runOnWorker(WorkerJob job) {
  running_ = true;
  Q_EMIT busyChanged(true);
  ReamEngine* engine = engine_.get();
  const BoneState state = bone_->current();  // immutable value: safe on the worker
  const std::uint64_t revision = bone_->currentRevision(), generation = engineGeneration_;
  watcher_.setFuture(QtConcurrent::run([engine, state, revision, generation, job = std::move(job)] {
    StepResult r;
    r.revision = revision;
    r.engineGeneration = generation;
    QElapsedTimer timer;
    timer.start();
    try {
      job(*engine, state, revision, r);
    } catch (const ReamCancelled&) {
      r.cancelled = true;
    } catch (const std::exception& e) {
      r.error = QString::fromStdString(e.what());
    }
    r.computeMs = timer.nsecsElapsed() / 1e6;
    return r;
  }));
}

void ReamSession::answerSearch(const StepResult& r) {
  ContactSearch answer;
  if (!r.error.isEmpty()) {
    answer.outcome = ContactSearch::Outcome::Failed;
    answer.error = r.error;
  } else if (r.revision != bone_->currentRevision() || r.engineGeneration != engineGeneration_) {
    answer.outcome = ContactSearch::Outcome::Dropped;  // the bone or the reamer changed while it ran
  } else if (r.approachMm) {
    answer.outcome = ContactSearch::Outcome::Found;
    answer.approachMm = *r.approachMm;
  } else {
    answer.outcome = ContactSearch::Outcome::NoneInReach;
  }
  Q_EMIT contactSearched(answer);
}

void ReamSession::finished() {
  running_ = false;
  progressTimer_->stop();
  StepResult r = watcher_.result();
  if (r.searchMm) {
    // A reamer chosen while the search ran takes over first: the search, made for the other one, is dropped.
    if (pendingReamer_) takeReamer(pendingReamer_->spec, pendingReamer_->cuttingVolume);
    answerSearch(r);
    startNext();
    return;
  }
  const bool clearStep = std::exchange(runningClear_, false);
  const bool noRoom = r.clear && (r.clear->outcome == ClearPlacement::Outcome::NoRoom ||
                                  r.clear->outcome == ClearPlacement::Outcome::Unsupported);
  const bool commits =
      !noRoom && !r.cancelled && r.error.isEmpty() && engine_ && r.computation.baseRevision == bone_->currentRevision();
  if (clearStep && !commits) {
    // A clear placement not made (no room, stopped, failed, or asked of a bone that has changed since): nothing is
    // placed, and the reamer goes back where it was last computed, not left at the pose asked, in the bone. Not
    // when a new bone or engine has come meanwhile (its own pose stands), nor over a newer move of the user's.
    if (!r.error.isEmpty()) {
      clearQueue();
      sequenceDone_ = sequenceTotal_ = 0;
      Q_EMIT progress(0, 0);
      Q_EMIT engineError(r.error);
    }
    if (r.engineGeneration == engineGeneration_) {
      lastComputedPose_ = poseBeforeRunning_;
      if (!latestUserPose_ && queued_.empty()) reamer_->setPose(poseBeforeRunning_ ? *poseBeforeRunning_ : poseBeforeClear_);
    }
    runningStep_.reset();
    Q_EMIT notPlacedClearOfBone(noRoom && r.clear->outcome == ClearPlacement::Outcome::Unsupported, !noRoom);
  } else if (r.cancelled) {
    // Stop: the step never happened, so the next one sweeps from where the bone was last cut and, unless a newer
    // move is pending, the reamer goes back there. Stopped because the bone changed (undo, another bone) it is
    // simply dropped, as a finished step would be.
    if (r.revision == bone_->currentRevision()) {
      lastComputedPose_ = poseBeforeRunning_;
      if (!latestUserPose_ && queued_.empty() && poseBeforeRunning_) reamer_->setPose(*poseBeforeRunning_);
      Q_EMIT stepCancelled();
    }
  } else if (!r.error.isEmpty()) {
    // The step never happened: as for Stop, the next one sweeps from where the bone was last computed (the path
    // the session records, and a replay of it, go on from there too).
    if (r.revision == bone_->currentRevision()) lastComputedPose_ = poseBeforeRunning_;
    // Stop the rest of a queued sequence: its steps would meet the same problem (one message, not one per step).
    clearQueue();
    sequenceDone_ = sequenceTotal_ = 0;
    Q_EMIT progress(0, 0);
    Q_EMIT engineError(r.error);
  } else if (engine_ && r.computation.baseRevision == bone_->currentRevision()) {
    Document::BatchScope batch(document_);
    const bool retreated = r.clear && r.clear->outcome == ClearPlacement::Outcome::Retreated;
    if (retreated) {  // placed out along the axis: that is where the reamer is, and where the path goes
      lastComputedPose_ = r.computation.pose;
      if (runningStep_) runningStep_->pose = r.computation.pose;
    }
    CommitOptions options;
    options.logEveryStep = false;  // the GUI's log lists cuts
    options.initialVolumeMm3 = initialVolumeMm3();
    options.note = runningNote_;  // a plan's note, on the row if the step makes one
    const CutLogEntry e = commitReamStep(document_, *bone_, *reamer_, *log_, alerts_, r.computation, steps_++, options);
    if (runningStep_) {
      runningStep_->stepIndex = e.stepIndex;
      runningStep_->timeUnixMs = e.timeUnixMs;
      path_.push_back(*std::exchange(runningStep_, std::nullopt));
    }
    pathRevision_ = bone_->currentRevision();
    if (e.boneStateId != 0) {
      engine_->adopt(e.boneStateId);
      ++cuts_;
      pushingOwnCommand_ = true;  // our own push is not an undo
      undo_.push(new CutCommand(*bone_, e));
      pushingOwnCommand_ = false;
    }
    // The step put the reamer where it was computed; a newer user move is where it really is.
    if (latestUserPose_) reamer_->setPose(*latestUserPose_);
    lastMinDistance_ = e.minDistanceMm;
    lastStepSwept_ = r.computation.swept;
    Q_EMIT stepFinished(e.minDistanceMm, e.contact);
    if (retreated) Q_EMIT placedOutward(r.clear->retreatMm);
    if (!runningNote_.empty()) Q_EMIT noteReached(QString::fromStdString(runningNote_));
  }  // else: computed against a bone that has changed since (undo, new bone): dropped
  if (sequenceTotal_ > 0) {
    ++sequenceDone_;
    Q_EMIT progress(sequenceDone_, sequenceTotal_);
  }
  if (pendingReamer_) takeReamer(pendingReamer_->spec, pendingReamer_->cuttingVolume);  // chosen while this ran
  startNext();
}

}  // namespace reamsim::ui
