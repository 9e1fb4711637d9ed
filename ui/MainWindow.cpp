#include "MainWindow.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QStandardPaths>
#include <QStatusBar>
#include <QToolBar>
#include <QUndoView>
#include <cmath>

#include "OtherBonesLayer.h"
#include "PluginHost.h"
#include "RecoveryFiles.h"
#include "reamsim/core/HistoryJournal.h"

namespace reamsim::ui {

MainWindow::MainWindow(const PluginHost& plugins, bool useStoredSettings, QWidget* parent)
    : QMainWindow(parent), plugins_(plugins), persistent_(useStoredSettings) {
  setObjectName("ReamSimMainWindow");
  session_ = std::make_unique<ReamSession>(plugins_);
  view_ = new BoneView(*session_, this);
  setCentralWidget(view_);
  if (persistent_) {
    QSettings settings;
    view_->setRenderSettings(RenderSettings::load(settings));
    recent_ = settings.value("recent_files").toStringList();
  }
  buildActions();
  buildMenus();
  buildDocks();
  buildStatusBar();
  buildVolumeImport();
  loadKeyBindings();
  setAcceptDrops(true);
  view_->setFocusPolicy(Qt::StrongFocus);
  view_->setFocus();

  connect(view_, &BoneView::reamerDragged, this, &MainWindow::dragReamer);
  // A move by hand is drawn before its step is computed (ReamSession::setFrameGate).
  session_->setFrameGate(true);
  connect(view_, &QOpenGLWidget::frameSwapped, session_.get(), &ReamSession::frameShown);
  connect(session_.get(), &ReamSession::stepFinished, this, [this] { updateStatus(); });
  connect(session_.get(), &ReamSession::contactSearched, this, &MainWindow::contactSearched);
  connect(session_.get(), &ReamSession::engineError, this, [this](const QString& m) {
    showError(tr("Cutting failed"), tr("The cutting engine reported an error; the bone is unchanged.\n\n%1").arg(m));
  });
  connect(session_.get(), &ReamSession::stepCancelled, this, [this] {
    statusBar()->showMessage(tr("Step stopped: the bone is unchanged"), 5000);
  });
  // A long step (a swing's chain of Booleans) shows its own progress when no sequence is running.
  connect(session_.get(), &ReamSession::stepProgress, this, [this](int done, int total) {
    if (sequenceShown_) return;
    progress_->setVisible(true);
    progress_->setRange(0, total);
    progress_->setValue(done);
  });
  // A sequence of one step ("Ream to depth" with one step, a plan of one pose) has nothing to count but the
  // step itself: the bar runs as busy until the step reports its own Booleans (a swing) or ends.
  connect(session_.get(), &ReamSession::progress, this, [this](int done, int total) {
    sequenceShown_ = total > 1;
    progress_->setVisible(total > 0);
    progress_->setRange(0, total > 1 ? total : 0);
    progress_->setValue(done);
  });
  connect(session_.get(), &ReamSession::busyChanged, this, [this](bool busy) {
    engineLabel_->setText(busy ? tr("computing…") : session_->cuttingStatus());
    if (!busy) {
      progress_->setVisible(false);
      sequenceShown_ = false;  // a finished sequence does not report (0, 0): it just goes idle
    }
  });
  connect(&importWatcher_, &QFutureWatcher<ImportOutcome>::finished, this, &MainWindow::importFinished);
  alertSubscription_ = session_->document().observeNode(session_->alerts()->id(), [this] { updateStatus(); });
  // The title's [*] marks unsaved changes: the undo history away from the point where the bone was opened
  // or last saved, or landmarks placed since.
  // An undo or redo changes the bone before the stack's index moves, and a landmark edit on the stack is not a
  // change of the bone: the title is asked again whenever the index has moved.
  connect(session_->undoStack(), &QUndoStack::indexChanged, this, [this] {
    if (isWindowModified() != hasUnsavedChanges()) updateTitle();
  });
  connect(session_->undoStack(), &QUndoStack::cleanChanged, this, [this] { updateTitle(); });  // a save, a restore
  landmarksTitleSubscription_ = session_->document().observeNode(session_->bone()->id(), [this] {
    if (isWindowModified() != hasUnsavedChanges()) updateTitle();
  });
  notesSubscription_ = session_->document().subscribe([this](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Log && isWindowModified() != hasUnsavedChanges()) updateTitle();
  });
  connect(session_.get(), &ReamSession::editNotRecorded, this,
          [this](const QString& message) { statusBar()->showMessage(message, 10000); });
  connect(session_.get(), &ReamSession::removalPreviewed, this, &MainWindow::removalPreviewed);
  connect(session_.get(), &ReamSession::placedOutward, this, [this](double mm) {
    statusBar()->showMessage(tr("Placed %L1 mm further out along the axis than asked: there, the reamer would have cut "
                                "the bone").arg(mm, 0, 'f', 2), 15000);
  });
  connect(session_.get(), &ReamSession::notPlacedClearOfBone, this, [this](bool unchecked, bool dropped) {
    statusBar()->showMessage(
        dropped     ? tr("The reamer is not moved: Aim's placement was stopped, or the bone changed while it searched")
        : unchecked ? tr("The reamer is not moved: the contact engine cannot tell where it would be clear of the bone")
                    : tr("The reamer is not moved: along the aimed axis it meets the bone for the next %1 mm out, and "
                         "placing it would cut it").arg(kClearPlacementReachMm),
        15000);
  });
  connect(session_.get(), &ReamSession::noteReached, this,
          [this](const QString& note) { statusBar()->showMessage(tr("Note: %1").arg(note), 10000); });
  updateStatus();
  updateTitle();
  resize(1280, 800);
  // A user's window keeps a crash-recovery copy of unsaved work (tests, demo and benchmarks turn it on
  // themselves, with a folder of their own).
  if (persistent_)
    enableRecovery(QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation) + "/recovery", kRecoveryDelayMs);
}

MainWindow::~MainWindow() {
  recoveryTimer_.stop();
  if (recoveryWrite_.isRunning()) recoveryWrite_.waitForFinished();  // it reads recovery_
  // Views and panels observe the session's document: they go first.
  alertSubscription_.reset();
  boneFrameSubscription_.reset();
  landmarksSubscription_.reset();
  landmarksTitleSubscription_.reset();
  notesSubscription_.reset();
  recoveryNotesSubscription_.reset();
  // The undo stack signals as it is destroyed with the session (cleanChanged): this window no longer listens.
  session_->undoStack()->disconnect(this);
  otherBones_.reset();
  if (importStop_) importStop_->store(true);  // a repair under way stops at its next check
  if (importWatcher_.isRunning()) importWatcher_.waitForFinished();
  for (QDockWidget* d : panels_) delete d;
  panels_.clear();
  delete historyDock_;
  delete takeCentralWidget();
  view_ = nullptr;
  session_.reset();
}

QAction* MainWindow::action(const QString& objectName) const { return findChild<QAction*>(objectName); }

void MainWindow::buildActions() {
  for (const MoveInfo& m : reamerMoves()) {
    auto* a = new QAction(tr(m.label), this);
    a->setObjectName(QString("reamer_") + m.id);
    a->setShortcut(QKeySequence(m.defaultKey));
    a->setShortcutContext(Qt::WindowShortcut);
    a->setAutoRepeat(true);
    const ReamerMove move = m.move;
    connect(a, &QAction::triggered, this, [this, move] { applyMove(move); });
    moveActions_.insert(static_cast<int>(move), a);
    addAction(a);
  }
}

void MainWindow::buildMenus() {
  auto add = [this](QMenu* menu, const QString& name, const QString& text, const QKeySequence& keys, auto slot) {
    auto* a = menu->addAction(text);
    a->setObjectName(name);
    if (!keys.isEmpty()) a->setShortcut(keys);
    connect(a, &QAction::triggered, this, slot);
    return a;
  };
  QMenu* file = menuBar()->addMenu(tr("&File"));
  add(file, "open", tr("&Open bone…"), QKeySequence::Open, [this] {
    if (!plugins_.meshImport()) return showError(tr("Open"), tr("No mesh import plugin is loaded (Help → Plugins)."));
    if (!confirmDiscardChanges(tr("open another bone"))) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open bone mesh"), {},
                                                      plugins_.meshImport()->nameFilters().join(";;"));
    if (!path.isEmpty()) openFile(path, true);
  })->setEnabled(plugins_.meshImport() != nullptr);
  add(file, "open_no_repair", tr("Open &without repair (view only)…"), {}, [this] {
    if (!confirmDiscardChanges(tr("open another bone"))) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open bone mesh (no repair, no cutting)"), {},
                                                      plugins_.meshImport()->nameFilters().join(";;"));
    if (!path.isEmpty()) openFile(path, false);
  })->setEnabled(plugins_.meshImport() != nullptr);
  recentMenu_ = file->addMenu(tr("Open &recent"));
  connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::rebuildRecentMenu);
  add(file, "load_default", tr("Load the &default case"), {}, [this] {
    if (confirmDiscardChanges(tr("load the default case"))) loadDefaultCase();
  });
  add(file, "save_again", tr("&Save"), QKeySequence::Save, [this] { saveBone(); })
      ->setEnabled(plugins_.meshImport() != nullptr);
  add(file, "save", tr("Save bone &as…"), QKeySequence::SaveAs, [this] {
    saveBoneAndCutLogInteractive();
  })->setEnabled(plugins_.meshImport() != nullptr);
  add(file, "export_report", tr("Export a &report…"), {}, [this] { exportReportInteractive(); });
  add(file, "export_path", tr("Export the reamer's &path as a plan…"), {}, [this] { exportPathInteractive(); });
  file->addSeparator();
  add(file, "quit", tr("&Quit"), QKeySequence::Quit, [this] { close(); });

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = session_->undoStack()->createUndoAction(this, tr("&Undo"));
  undo->setObjectName("undo");
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = session_->undoStack()->createRedoAction(this, tr("&Redo"));
  redo->setObjectName("redo");
  redo->setShortcuts({QKeySequence::Redo, QKeySequence("Ctrl+Y")});
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  add(edit, "key_bindings", tr("&Key bindings…"), {}, [this] { editKeyBindings(); });

  QMenu* view = menuBar()->addMenu(tr("&View"));
  add(view, "view_anterior", tr("&Anterior"), QKeySequence("1"), [this] { view_->setStandardView(BoneView::StandardView::Anterior); });
  add(view, "view_posterior", tr("&Posterior"), QKeySequence("2"), [this] { view_->setStandardView(BoneView::StandardView::Posterior); });
  add(view, "view_superior", tr("&Superior"), QKeySequence("3"), [this] { view_->setStandardView(BoneView::StandardView::Superior); });
  add(view, "view_en_face", tr("&En face (planned axis)"), QKeySequence("4"), [this] { view_->setStandardView(BoneView::StandardView::EnFace); });
  add(view, "view_reset", tr("&Reset view"), QKeySequence("0"), [this] { view_->resetView(); });
  view->addSeparator();
  QAction* wire = add(view, "wireframe", tr("&Wireframe"), QKeySequence("W"), [this](bool on) { view_->setWireframe(on); });
  wire->setCheckable(true);
  QAction* depth = add(view, "depth_colouring", tr("&Depth colouring (removed mm)"), QKeySequence("C"), [this](bool on) {
    view_->setColourMode(on ? BoneView::ColourMode::Depth : BoneView::ColourMode::Surface);
  });
  depth->setCheckable(true);
  add(view, "render_settings", tr("Colours, material and &lights…"), {}, [this] { editRenderSettings(); });
  view->addSeparator();
  viewMenuForDocks_ = view;

  QMenu* reamer = menuBar()->addMenu(tr("&Reamer"));
  for (const MoveInfo& m : reamerMoves()) reamer->addAction(moveActions_.value(static_cast<int>(m.move)));
  reamer->addSeparator();
  add(reamer, "ream_to_depth", tr("Ream to &depth below first contact…"), QKeySequence("Ctrl+D"),
      [this] { askReamToDepth(); });
  add(reamer, "feed_by", tr("&Feed along the axis by…"), QKeySequence("Ctrl+F"), [this] { askFeedBy(); });
  add(reamer, "preview_ream_to_depth", tr("Pre&view ream to depth…"), QKeySequence("Ctrl+Shift+D"),
      [this] { askPreviewReamToDepth(); });
  add(reamer, "run_plan", tr("Run a &plan…"), QKeySequence("Ctrl+Shift+P"), [this] { runPlanFile(); });
  add(reamer, "replay_plan", tr("&Replay a recorded path at its pace…"), {},
      [this] { runPlanFile({}, PlanPace::AsRecorded); });
  QMenu* speeds = reamer->addMenu(tr("Replay s&peed"));
  replaySpeeds_ = new QActionGroup(this);
  for (double speed : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0}) {
    QAction* a = speeds->addAction(speed == 1.0 ? tr("1× (as recorded)") : tr("%1×").arg(QLocale().toString(speed)));
    a->setObjectName(QString("replay_speed_%1").arg(speed * 100));
    a->setCheckable(true);
    a->setData(speed);
    replaySpeeds_->addAction(a);
    connect(a, &QAction::triggered, this, [this, speed] { setReplaySpeed(speed); });
  }
  setReplaySpeed(persistent_ ? QSettings().value("replay_speed", 1.0).toDouble() : 1.0);
  reamer->addSeparator();
  add(reamer, "choose_reamer", tr("&Choose the reamer…"), QKeySequence("Ctrl+Shift+R"), [this] { chooseReamer(); });
  add(reamer, "choose_reamer_mesh", tr("Choose a reamer &mesh…"), {}, [this] { chooseReamerMesh(); })
      ->setEnabled(plugins_.meshImport() != nullptr);
  add(reamer, "stop", tr("&Stop steps"), QKeySequence("Esc"), [this] {
    session_->cancelQueued();
    session_->cancelPreview();
    pendingDepth_.reset();  // a ream to depth whose search is running: its answer must not start the feed
  });

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  add(help, "plugins", tr("&Plugins…"), {}, [this] { showPluginsDialog(); });
  add(help, "about", tr("&About ReamSim"), {}, [this] {
    QMessageBox::about(this, tr("About ReamSim"),
                       tr("ReamSim — glenoid reaming simulator.\nOrthographic views; exact mesh Booleans."));
  });

  QToolBar* steps = addToolBar(tr("Steps"));
  steps->setObjectName("StepsToolBar");
  auto spin = [&](const QString& name, const QString& label, double value, double max, const QString& suffix) {
    steps->addWidget(new QLabel(label, steps));
    auto* s = new QDoubleSpinBox(steps);
    s->setObjectName(name);
    s->setDecimals(2);
    s->setRange(0.01, max);
    s->setValue(value);
    s->setSuffix(suffix);
    s->setFocusPolicy(Qt::ClickFocus);
    steps->addWidget(s);
    return s;
  };
  moveStep_ = spin("move_step", tr(" Move "), 0.5, 50, " mm");
  rotateStep_ = spin("rotate_step", tr(" Rotate "), 2.0, 90, "°");
  feedStep_ = spin("feed_step", tr(" Feed "), 0.2, 10, " mm");
  if (persistent_) {
    QSettings s;
    setSteps(s.value("steps/move_mm", 0.5).toDouble(), s.value("steps/rotate_deg", 2.0).toDouble(),
             s.value("steps/feed_mm", 0.2).toDouble());
    for (QDoubleSpinBox* b : {moveStep_, rotateStep_, feedStep_})
      connect(b, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] {
        QSettings s;
        s.setValue("steps/move_mm", moveStep_->value());
        s.setValue("steps/rotate_deg", rotateStep_->value());
        s.setValue("steps/feed_mm", feedStep_->value());
      });
  }
}

void MainWindow::buildDocks() {
  historyDock_ = new QDockWidget(tr("History"), this);
  historyDock_->setObjectName("HistoryDock");
  auto* undoView = new QUndoView(session_->undoStack(), historyDock_);
  undoView->setObjectName("HistoryView");
  undoView->setEmptyLabel(tr("imported bone"));
  undoView->setFocusPolicy(Qt::NoFocus);
  historyDock_->setWidget(undoView);
  addDockWidget(Qt::RightDockWidgetArea, historyDock_);
  viewMenuForDocks_->addAction(historyDock_->toggleViewAction());
  for (PanelInterface* p : plugins_.panels()) {
    QDockWidget* dock = p->createPanel(session_->document(), this);
    if (!dock) continue;
    panels_.push_back(dock);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    // A tall dock (the Planning one) shares the History's place as a tab, so that the cut log keeps its rows.
    if (dock->objectName() == "PlanningPanel") {
      tabifyDockWidget(historyDock_, dock);
      dock->raise();
    }
    viewMenuForDocks_->addAction(dock->toggleViewAction());
  }
}

void MainWindow::buildStatusBar() {
  alertLabel_ = new QLabel(this);
  alertLabel_->setObjectName("AlertLabel");
  alertLabel_->setMinimumWidth(140);
  distanceLabel_ = new QLabel(this);
  distanceLabel_->setObjectName("DistanceLabel");
  distanceLabel_->setMinimumWidth(170);
  engineLabel_ = new QLabel(this);
  engineLabel_->setObjectName("EngineLabel");
  importBusy_ = new QProgressBar(this);
  importBusy_->setObjectName("ImportProgress");
  importBusy_->setRange(0, 0);  // busy: the importer reports no fraction
  importBusy_->setMaximumWidth(120);
  importBusy_->setVisible(false);
  importCancel_ = new QPushButton(tr("Cancel import"), this);
  importCancel_->setObjectName("CancelImport");
  importCancel_->setVisible(false);
  connect(importCancel_, &QPushButton::clicked, this, &MainWindow::cancelImport);
  statusBar()->addPermanentWidget(importBusy_);
  statusBar()->addPermanentWidget(importCancel_);
  progress_ = new QProgressBar(this);
  progress_->setObjectName("StepProgress");
  progress_->setMaximumWidth(160);
  progress_->setVisible(false);
  statusBar()->addPermanentWidget(engineLabel_, 1);
  statusBar()->addPermanentWidget(progress_);
  statusBar()->addPermanentWidget(distanceLabel_);
  statusBar()->addPermanentWidget(alertLabel_);
}

// The thesis's alerts from the AlertNode, with the live minimum distance of the last collision query.
void MainWindow::updateStatus() {
  const AlertNode* alerts = session_->alerts();
  if (alerts->has(AlertKind::Contact)) {
    alertLabel_->setText(tr("CONTACT"));
    alertLabel_->setStyleSheet("QLabel { color: white; background: #c0392b; padding: 1px 6px; }");
  } else if (alerts->has(AlertKind::BoundsOverlap)) {
    alertLabel_->setText(tr("boxes overlap"));
    alertLabel_->setStyleSheet("QLabel { color: black; background: #f39c12; padding: 1px 6px; }");
  } else {
    alertLabel_->setText(session_->canCollide() ? tr("clear") : tr("no collision"));
    alertLabel_->setStyleSheet({});
  }
  const double d = session_->lastMinDistanceMm();
  distanceLabel_->setText(std::isfinite(d) ? tr("min distance %L1 mm").arg(d, 0, 'f', 2) : tr("min distance —"));
  if (!session_->busy()) engineLabel_->setText(session_->cuttingStatus());
}

QString MainWindow::statusAlertText() const { return alertLabel_->text(); }
QString MainWindow::statusDistanceText() const { return distanceLabel_->text(); }

void MainWindow::updateTitle() {
  setWindowTitle(boneName_.isEmpty() ? tr("ReamSim[*]") : tr("ReamSim — %1[*]").arg(boneName_));
  setWindowModified(hasUnsavedChanges());
}

void MainWindow::showError(const QString& title, const QString& message) {
  lastError_ = message;
  statusBar()->showMessage(title + ": " + message.section('\n', 0, 0), 10000);
  // Non-blocking (window-modal): the event loop, the worker and the tests keep running.
  auto* box = new QMessageBox(QMessageBox::Critical, title, message, QMessageBox::Ok, this);
  box->setObjectName("ErrorDialog");
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

}  // namespace reamsim::ui
