// MainWindow: reamer control — the thesis keys (remappable), Ctrl-drag along the axis, feed, ream to depth.
#include <QAction>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QDir>
#include <QFileInfo>
#include <QInputDialog>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "MainWindow.h"
#include "PluginHost.h"
#include "SettingsDialogs.h"
#include "reamsim/core/PlanNode.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/tools/ReamerFile.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::ui {

// Where the reamer will be once everything requested has run: the next key press starts from there.
Pose MainWindow::targetPose() const { return session_->targetPose(); }

// A move or feed starts from where the reamer is or will be; while Aim's placement is searching for room clear of
// the bone (milliseconds), that is not known yet: the request is not taken, and the status bar says so.
bool MainWindow::waitingForClearPlacement() {
  if (!session_->placingClearOfBone()) return false;
  statusBar()->showMessage(tr("Aim is placing the reamer clear of the bone: try again in a moment"), 3000);
  return true;
}

void MainWindow::applyMove(ReamerMove move) {
  if (waitingForClearPlacement()) return;
  const bool feed = move == ReamerMove::FeedForward || move == ReamerMove::FeedBack;
  if (feed) {
    // Every feed step is cut, none is skipped: it continues from the last queued pose. A held key repeats
    // faster than cuts finish: beyond a few queued steps the press is ignored rather than queued without end.
    if (session_->queuedSteps() >= kMaxQueuedFeedSteps) {
      statusBar()->showMessage(tr("Feed: %1 steps are still queued; press Esc to stop them").arg(session_->queuedSteps()),
                               2000);
      return;
    }
    session_->runSteps({reamsim::ui::applyMove(targetPose(), move, feedStep_->value(), rotateStep_->value())});
  } else {
    // A move by hand starts where the reamer is shown (not at the end of a queued feed, which it interrupts);
    // coalesced: the latest pose wins while a step runs.
    session_->moveReamer(reamsim::ui::applyMove(session_->reamer()->pose(), move, moveStep_->value(), rotateStep_->value()),
                         true);
  }
}

void MainWindow::dragReamer(double mm) {
  if (waitingForClearPlacement()) return;
  session_->moveReamer(advancedAlongAxis(session_->reamer()->pose(), mm), true);
}

bool MainWindow::chooseReamer(const QString& preset) {
  std::vector<ReamerSpec> presets;
  try {
    presets = loadPresets(reamerPresetsPath());
  } catch (const std::exception& e) {
    showError(tr("Choose the reamer"), QString::fromStdString(e.what()));
    return false;
  }
  if (presets.empty()) {
    showError(tr("Choose the reamer"), tr("%1 lists no reamers.").arg(QString::fromStdString(reamerPresetsPath())));
    return false;
  }
  const auto describe = [](const ReamerSpec& r) {
    if (!r.meshFile.empty())
      return tr("%1 (a mesh: %2)").arg(QString::fromStdString(r.name), QFileInfo(QString::fromStdString(r.meshFile)).fileName());
    return r.isFlat() ? tr("%1 (Ø %L2 mm, flat)").arg(QString::fromStdString(r.name)).arg(r.diameterMm)
                      : tr("%1 (Ø %L2 mm, cap sphere R %L3 mm)").arg(QString::fromStdString(r.name)).arg(r.diameterMm).arg(r.sphereRadiusMm);
  };
  QString name = preset;
  if (name.isEmpty()) {
    QStringList items;
    int current = 0;
    for (const ReamerSpec& r : presets) {
      if (r.name == session_->reamer()->spec().name) current = items.size();
      items << describe(r);
    }
    bool ok = false;
    const QString picked = QInputDialog::getItem(this, tr("Choose the reamer"),
                                                 tr("The reamer to cut with (it keeps the current pose and axis):"),
                                                 items, current, false, &ok);
    const int index = items.indexOf(picked);
    if (!ok || index < 0) return false;
    name = QString::fromStdString(presets[std::size_t(index)].name);
  }
  const auto it = std::find_if(presets.begin(), presets.end(), [&](const ReamerSpec& r) { return r.name == name.toStdString(); });
  if (it == presets.end()) {
    showError(tr("Choose the reamer"), tr("There is no reamer %1 in %2.").arg(name, QString::fromStdString(reamerPresetsPath())));
    return false;
  }
  if (it->name == session_->reamer()->spec().name && it->meshFile == session_->reamer()->spec().meshFile) return false;
  return takeReamer(*it, describe(*it));
}

bool MainWindow::chooseReamerMesh(const QString& path) {
  QString file = path;
  if (file.isEmpty() && plugins_.meshImport())
    file = QFileDialog::getOpenFileName(this, tr("Choose a reamer mesh (a closed solid: tip at the origin, feed along +Z)"),
                                        {}, plugins_.meshImport()->nameFilters().join(";;"));
  if (file.isEmpty()) return false;
  return takeReamer(meshReamerSpec(file.toStdString()), tr("%1 (a mesh)").arg(QFileInfo(file).fileName()));
}

// The reamer keeps its pose; one that cannot be made (a mesh that is not a closed solid) leaves the reamer as it was.
bool MainWindow::takeReamer(const ReamerSpec& spec, const QString& description) {
  try {
    session_->setReamer(spec);
  } catch (const std::exception& e) {
    showError(tr("Choose the reamer"), QString::fromStdString(e.what()));
    return false;
  }
  session_->plan()->setReamerSpecName(spec.name);
  statusBar()->showMessage(tr("Reamer: %1; the next cut is made with it").arg(description), 5000);
  return true;
}

// A plan's reamer as the command line takes it (a mesh file if there is one, otherwise a preset name), a mesh
// beside the plan first.
ReamerSpec MainWindow::planReamer(const std::string& reamer, const QString& planFile) const {
  const QString beside = QFileInfo(planFile).dir().filePath(QString::fromStdString(reamer));
  if (QFileInfo(beside).isFile()) return meshReamerSpec(beside.toStdString());
  return reamerFromArgument(reamer, reamerPresetsPath());
}

bool MainWindow::runPlanFile(const QString& path, PlanPace pace) {
  const bool paced = pace == PlanPace::AsRecorded;
  QString file = path;
  if (file.isEmpty())
    file = QFileDialog::getOpenFileName(this, paced ? tr("Replay a recorded path") : tr("Run a plan"), {}, tr("Plans (*.json)"));
  if (file.isEmpty()) return false;
  const QString title = tr("Cannot run the plan %1").arg(QFileInfo(file).fileName());
  ReamPlan plan;
  std::vector<Pose> poses;
  try {
    plan = loadPlan(file.toStdString());
    poses = plan.expandedPoses();
    if (poses.empty()) throw InputError(file.toStdString(), "the plan has no poses");
    if (paced && !plan.hasTimes())
      throw InputError(file.toStdString(), "no pose has a recorded time (t_ms), so there is no pace to replay it at: "
                                           "run it as a plan, or export a path from a session (File menu)");
  } catch (const std::exception& e) {
    showError(title, QString::fromStdString(e.what()));
    return false;
  }
  if (!session_->canCollide()) {  // before anything changes
    showError(title, session_->cuttingStatus());
    return false;
  }
  if (!plan.reamer.empty()) {
    ReamerSpec spec;
    try {
      spec = planReamer(plan.reamer, file);
    } catch (const std::exception& e) {
      showError(title, tr("Its reamer %1 is neither a mesh file nor a preset:\n%2")
                           .arg(QString::fromStdString(plan.reamer), QString::fromStdString(e.what())));
      return false;
    }
    const ReamerSpec& now = session_->reamer()->spec();
    try {
      if (spec.name != now.name || spec.meshFile != now.meshFile) session_->setReamer(spec);
    } catch (const std::exception& e) {  // a mesh that is not a closed solid
      showError(title, QString::fromStdString(e.what()));
      return false;
    }
  }
  {
    Document::BatchScope batch(session_->document());
    session_->plan()->setReamerSpecName(session_->reamer()->spec().name);
    session_->plan()->setPoses(poses);
    session_->plan()->setFeedDescription(plan.description.empty() ? std::nullopt : std::optional<std::string>(plan.description));
  }
  // As the command line's controller: the first pose is placed (nothing swept to it), the rest is a path. What was
  // waiting goes (a queued feed, a move not yet computed, a ream to depth whose search is out).
  pendingDepth_.reset();
  session_->cancelQueued();
  session_->runPlan(plan, paced ? replaySpeed_ : 0.0);
  statusBar()->showMessage(
      (paced ? tr("Replaying %1 at %2× its recorded pace: %Ln step(s)", "", int(poses.size()))
                   .arg(QFileInfo(file).fileName(), QLocale().toString(replaySpeed_))
             : tr("Running %1: %Ln step(s)", "", int(poses.size())).arg(QFileInfo(file).fileName())),
      5000);
  return true;
}

void MainWindow::setReplaySpeed(double speed) {
  if (!(speed >= 1.0 / 64 && speed <= 64)) return;  // a stored value gone wrong: the speed stays
  replaySpeed_ = speed;
  if (replaySpeeds_)
    for (QAction* a : replaySpeeds_->actions()) a->setChecked(a->data().toDouble() == speed);
  if (persistent_) QSettings().setValue("replay_speed", speed);
}

QString MainWindow::exportPath(const QString& file) {
  const std::vector<ReamSession::PathStep>& path = session_->path();
  if (path.empty()) return tr("The reamer has made no step on this bone yet: there is no path to export.");
  const ReamerSpec& reamer = path.front().reamer;
  for (std::size_t i = 1; i < path.size(); ++i)
    if (path[i].reamer.name != reamer.name || path[i].reamer.meshFile != reamer.meshFile)
      return tr("The reamer changed at step %1 (%2 to %3): a plan has one reamer, so this path cannot be one plan.")
          .arg(i + 1)
          .arg(QString::fromStdString(reamer.name), QString::fromStdString(path[i].reamer.name));
  ReamPlan plan;
  plan.reamer = reamer.meshFile.empty() ? reamer.name : reamer.meshFile;
  std::unordered_map<std::size_t, std::string> notes;  // by step: the log's rows are the steps that cut
  for (const CutLogEntry& row : session_->log()->entries())
    if (!row.note.empty()) notes[row.stepIndex] = row.note;
  bool anyNote = false;
  for (std::size_t i = 0; i < path.size(); ++i) {
    plan.poses.push_back(path[i].pose);
    if (path[i].placed) plan.placedPoses.push_back(i);
    const auto note = notes.find(path[i].stepIndex);
    plan.poseNotes.push_back(note == notes.end() ? std::string() : note->second);
    anyNote = anyNote || note != notes.end();
    // The pace it was made at, from its first step: a clock set back meanwhile cannot make time go back, and one
    // moved on by days (a machine asleep) cannot take the time past what a plan may hold (PLAN_FORMAT.md).
    const double sinceFirst = std::min(double(path[i].timeUnixMs - path.front().timeUnixMs), kMaxPlanTimeMs);
    plan.poseTimesMs.push_back(std::max(sinceFirst, i > 0 ? plan.poseTimesMs.back().value_or(0.0) : 0.0));
  }
  if (!anyNote) plan.poseNotes.clear();
  const QString start = session_->pathStart() == ReamSession::PathStart::AsOpened
                            ? tr("the bone as it was opened")
                        : session_->pathStart() == ReamSession::PathStart::AsRecovered
                            ? tr("the bone as it was restored from the crash-recovery copy (save it to have it as a file)")
                            : tr("the bone as it stood when the path began (an undo, a redo or a bone exchanged had "
                                 "changed it since it was opened or restored)");
  plan.description = tr("The reamer's path in ReamSim on %1: %2 steps, each a move from the one before or, where "
                        "marked placed, a placement. Run on %4, it makes the same cuts.%3")
                         .arg(boneName_)
                         .arg(path.size())
                         .arg(session_->pathInterrupted()
                                  ? tr(" Steps were undone or the bone was exchanged during the session: the replay "
                                       "runs every step on one bone and ends elsewhere.")
                                  : QString(),
                              start)
                         .toStdString();
  return writeTextReporting(file, planToJson(plan));
}

void MainWindow::exportPathInteractive() {
  const QString file =
      QFileDialog::getSaveFileName(this, tr("Export the reamer's path as a plan"), "path_plan.json", tr("Plans (*.json)"));
  if (file.isEmpty()) return;
  const QString error = exportPath(file);
  if (!error.isEmpty()) return showError(tr("Export the reamer's path"), error);
  statusBar()->showMessage(session_->pathInterrupted()
                               ? tr("Path written to %1 (steps were undone: its replay differs, see its description)").arg(file)
                               : tr("Path written to %1").arg(file),
                           8000);
}

void MainWindow::feedBy(double mm) {
  if (!(mm > 0) || waitingForClearPlacement()) return;
  session_->runSteps(reamToDepthPoses(targetPose(), 0.0, mm, feedStep_->value()));
}

// Depth below the first contact: the session searches the contact on its worker, with the collision
// structure that already follows the bone, then the reamer moves to it and feeds in feed steps.
void MainWindow::reamToDepth(double depthMm) {
  if (!(depthMm > 0) || pendingDepth_ || waitingForClearPlacement()) return;
  if (!session_->reamer()->cuttingVolume() || session_->bone()->current().empty()) {
    showError(tr("Ream to depth"), tr("There is no bone or no reamer to ream with."));
    return;
  }
  const Pose start = targetPose();
  statusBar()->showMessage(tr("Searching the first contact along the reamer axis…"));
  pendingDepth_ = PendingDepth{start, depthMm};
  session_->searchContactAlongAxis(start, kContactSearchMm);
}

void MainWindow::contactSearched(const ContactSearch& result) {
  const std::optional<PendingDepth> pending = std::exchange(pendingDepth_, std::nullopt);
  if (!pending) return;
  statusBar()->clearMessage();
  // Aim asked meanwhile: the reamer goes where it says, not back to the axis this depth was asked along.
  if (session_->placingClearOfBone()) return;
  switch (result.outcome) {
    case ContactSearch::Outcome::Dropped:  // the bone changed or the user moved on first
      return;
    case ContactSearch::Outcome::Failed:
      showError(tr("Ream to depth"), result.error);
      return;
    case ContactSearch::Outcome::NoneInReach:
      showError(tr("Ream to depth"),
                tr("The reamer meets no bone within %L1 mm along its axis: aim it at the bone first.").arg(kContactSearchMm));
      return;
    case ContactSearch::Outcome::Found:
      lastApproachMm_ = result.approachMm;
      session_->runSteps(reamToDepthPoses(pending->start, result.approachMm, pending->depthMm, feedStep_->value()));
      return;
  }
}

void MainWindow::askReamToDepth() {
  bool ok = false;
  const double depth = QInputDialog::getDouble(this, tr("Ream to depth"),
                                               tr("Ream to this depth below the first contact along the reamer axis "
                                                  "(mm), in feed steps of %1 mm:")
                                                   .arg(feedStep_->value()),
                                               1.0, 0.01, 50.0, 2, &ok);
  if (ok) reamToDepth(depth);
}

void MainWindow::askPreviewReamToDepth() {
  bool ok = false;
  const double depth = QInputDialog::getDouble(this, tr("Preview ream to depth"),
                                               tr("How much bone would reaming to this depth below the first contact "
                                                  "along the reamer axis remove (mm, in feed steps of %1 mm)? The bone "
                                                  "is not cut.")
                                                   .arg(feedStep_->value()),
                                               1.0, 0.01, 50.0, 2, &ok);
  if (ok) previewReamToDepth(depth);
}

void MainWindow::previewReamToDepth(double depthMm) {
  if (waitingForClearPlacement()) return;
  lastPreviewText_.clear();
  statusBar()->showMessage(tr("Computing what reaming %L1 mm would remove, on a copy of the bone (Esc stops)…")
                               .arg(depthMm, 0, 'f', 2));
  session_->previewReamToDepth(targetPose(), depthMm, feedStep_->value());
}

void MainWindow::removalPreviewed(const RemovalPreviewAnswer& a) {
  using Outcome = RemovalPreviewAnswer::Outcome;
  statusBar()->clearMessage();
  if (a.outcome == Outcome::Cancelled) {
    statusBar()->showMessage(tr("Preview stopped"), 5000);
    return;
  }
  if (a.outcome == Outcome::Failed) {
    lastPreviewText_ = a.error;
    return showError(tr("Preview ream to depth"), a.error);
  }
  const RemovalPreview& p = a.preview;
  QLocale shown;
  if (!p.approachMm) {
    lastPreviewText_ = tr("The reamer meets no bone within %L1 mm along its axis: reaming to depth would remove nothing.")
                           .arg(ReamSession::kPreviewReachMm);
  } else {
    lastPreviewText_ =
        tr("Reaming %1 mm below the first contact (%2 mm ahead of the reamer along its axis) would remove %3 mm³ of "
           "bone in %4 step(s), %5 of them cutting; the bone would have %6 faces.")
            .arg(shown.toString(a.depthMm, 'f', 2), shown.toString(*p.approachMm, 'f', 2),
                 shown.toString(p.removedMm3, 'f', 1), shown.toString(qulonglong(p.steps)),
                 shown.toString(qulonglong(p.cuts)), shown.toString(qulonglong(p.facesAfter)));
    if (p.seat)  // as Measure seat would say after the ream: a face larger than the glenoid never seats whole
      lastPreviewText_ += tr(" The cutting face would sit on bone over %1 % of its area.")
                              .arg(shown.toString(100 * p.seat->seatedFraction, 'f', 1));
  }
  const bool stale = a.outcome == Outcome::Stale || !previewStillHolds(a);
  auto* box = new QMessageBox(QMessageBox::Information, tr("Preview ream to depth"), lastPreviewText_, QMessageBox::Close, this);
  box->setObjectName("RemovalPreviewDialog");
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->setInformativeText(stale ? tr("Computed for the bone, the reamer and its pose as they were when asked; one "
                                     "of them has changed since. Preview again for them as they are.")
                                : tr("Computed on a copy: the bone is not cut."));
  if (p.approachMm && !stale) {
    QPushButton* ream = box->addButton(tr("Ream it"), QMessageBox::AcceptRole);
    ream->setObjectName("ReamIt");
    // Checked again at the click: the box waits (and steps may run) while it is open.
    connect(ream, &QPushButton::clicked, this, [this, a] {
      if (!previewStillHolds(a))
        return showError(tr("Preview ream to depth"), tr("The bone, the reamer or its pose has changed since the "
                                                         "preview: nothing was cut. Preview again."));
      reamToDepth(a.depthMm);
    });
  }
  box->open();
}

// What a preview was computed for is still what Ream to depth would ream: the bone (its revision), the reamer (the
// session's engine generation), where the reamer is going and the feed step.
bool MainWindow::previewStillHolds(const RemovalPreviewAnswer& a) const {
  const Pose now = targetPose();
  return a.revision == session_->bone()->currentRevision() && a.generation == session_->engineGeneration() &&
         now.tip == a.start.tip && now.axis == a.start.axis && feedStep_->value() == a.stepMm && !session_->busy();
}

void MainWindow::askFeedBy() {
  bool ok = false;
  const double mm = QInputDialog::getDouble(this, tr("Feed by"),
                                            tr("Feed along the reamer axis by (mm), in steps of %L1 mm:")
                                                .arg(feedStep_->value()),
                                            2.0, 0.01, 50.0, 2, &ok);
  if (ok) feedBy(mm);
}

void MainWindow::setSteps(double moveMm, double rotateDeg, double feedMm) {
  moveStep_->setValue(moveMm);
  rotateStep_->setValue(rotateDeg);
  feedStep_->setValue(feedMm);
}

double MainWindow::feedStepMm() const { return feedStep_->value(); }

// The text of another action of this window bound to `keys` ("" when none): a key bound twice works for
// neither action (Qt reports an ambiguous shortcut), so such a binding is refused.
QString MainWindow::shortcutOwner(const QKeySequence& keys, const QList<const QAction*>& ignored) const {
  if (keys.isEmpty()) return {};
  for (const QAction* a : findChildren<QAction*>())
    if (!ignored.contains(a) && a->shortcut() == keys) return a->text().remove('&');
  return {};
}

bool MainWindow::setKeyBinding(ReamerMove move, const QKeySequence& keys) {
  QAction* a = moveAction(move);
  if (!a) return false;
  const QString owner = shortcutOwner(keys, {a});
  if (!owner.isEmpty()) {
    showError(tr("Key bindings"), tr("%1 is already bound to \"%2\"; the binding was not changed.")
                                      .arg(keys.toString(QKeySequence::NativeText), owner));
    return false;
  }
  a->setShortcut(keys);
  if (persistent_)
    for (const MoveInfo& m : reamerMoves())
      if (m.move == move) QSettings().setValue(QString("keys/") + m.id, keys.toString());
  return true;
}

void MainWindow::loadKeyBindings() {
  if (persistent_) applyStoredKeyBindings(QSettings());
}

void MainWindow::applyStoredKeyBindings(const QSettings& s) {
  // A stored key that a menu action has taken since it was stored (a newer version's shortcut) would work for
  // neither: the move keeps its default key, and the status bar says so.
  QList<const QAction*> moves;
  for (const MoveInfo& m : reamerMoves()) moves << moveAction(m.move);
  QStringList dropped;
  for (const MoveInfo& m : reamerMoves()) {
    const QString stored = s.value(QString("keys/") + m.id).toString();
    if (stored.isEmpty()) continue;
    const QKeySequence keys(stored);
    const QString owner = shortcutOwner(keys, moves);
    if (!owner.isEmpty()) {
      dropped << tr("%1 (%2, now \"%3\")").arg(tr(m.label), keys.toString(QKeySequence::NativeText), owner);
      continue;
    }
    moveAction(m.move)->setShortcut(keys);
  }
  if (!dropped.isEmpty())
    statusBar()->showMessage(tr("Stored keys not used, their moves keep their default keys: %1").arg(dropped.join(", ")), 20000);
}

void MainWindow::editKeyBindings() {
  KeyBindingsDialog dialog(this);
  for (const MoveInfo& m : reamerMoves()) dialog.addRow(m.id, tr(m.label), moveAction(m.move)->shortcut(), QKeySequence(m.defaultKey));
  if (dialog.exec() != QDialog::Accepted) return;
  // Check the whole new set first: twice within it, or taken by an action that is not a reamer move.
  QList<const QAction*> moves;
  for (const MoveInfo& m : reamerMoves()) moves << moveAction(m.move);
  QMap<QString, QString> seen;
  QStringList clashes;
  for (const MoveInfo& m : reamerMoves()) {
    const QKeySequence keys = dialog.keys(m.id);
    if (keys.isEmpty()) continue;
    const QString text = keys.toString(QKeySequence::NativeText);
    if (seen.contains(text)) clashes << tr("%1: \"%2\" and \"%3\"").arg(text, seen[text], tr(m.label));
    seen[text] = tr(m.label);
    const QString owner = shortcutOwner(keys, moves);
    if (!owner.isEmpty()) clashes << tr("%1: \"%2\" and \"%3\"").arg(text, tr(m.label), owner);
  }
  if (!clashes.isEmpty()) {
    showError(tr("Key bindings"), tr("Each key can do one thing; nothing was changed:\n") + clashes.join('\n'));
    return;
  }
  for (const MoveInfo& m : reamerMoves()) moveAction(m.move)->setShortcut({});  // no transient clashes
  for (const MoveInfo& m : reamerMoves()) setKeyBinding(m.move, dialog.keys(m.id));
}

void MainWindow::editRenderSettings() {
  RenderSettingsDialog dialog(view_->renderSettings(), this);
  connect(&dialog, &RenderSettingsDialog::changed, view_, &BoneView::setRenderSettings);
  const RenderSettings before = view_->renderSettings();
  if (dialog.exec() != QDialog::Accepted) {
    view_->setRenderSettings(before);
    return;
  }
  view_->setRenderSettings(dialog.settings());
  if (persistent_) {
    QSettings s;
    dialog.settings().save(s);
  }
}

}  // namespace reamsim::ui
