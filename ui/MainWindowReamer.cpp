// MainWindow: reamer control — the thesis keys (remappable), Ctrl-drag along the axis, feed, ream to depth.
#include <QAction>
#include <QDoubleSpinBox>
#include <QInputDialog>
#include <QSettings>
#include <cmath>

#include "MainWindow.h"
#include "SettingsDialogs.h"

namespace reamsim::ui {

// Where the reamer will be once everything requested has run: the next key press starts from there.
Pose MainWindow::targetPose() const { return session_->targetPose(); }

void MainWindow::applyMove(ReamerMove move) {
  const bool feed = move == ReamerMove::FeedForward || move == ReamerMove::FeedBack;
  const Pose next = reamsim::ui::applyMove(targetPose(), move, feed ? feedStep_->value() : moveStep_->value(),
                                           rotateStep_->value());
  if (feed) {
    session_->runSteps({next});  // every feed step is cut, none is skipped
  } else {
    session_->moveReamer(next);  // coalesced: the latest pose wins while a step runs
  }
}

void MainWindow::dragReamer(double mm) { session_->moveReamer(advancedAlongAxis(targetPose(), mm)); }

void MainWindow::reamToDepth(double depthMm) {
  if (!(depthMm > 0)) return;
  const double step = feedStep_->value();
  const Pose start = targetPose();
  std::vector<Pose> poses;
  const int n = static_cast<int>(std::ceil(depthMm / step - 1e-9));
  for (int i = 1; i <= n; ++i) poses.push_back(advancedAlongAxis(start, std::min(depthMm, i * step)));
  session_->runSteps(poses);
}

void MainWindow::askReamToDepth() {
  bool ok = false;
  const double depth = QInputDialog::getDouble(this, tr("Ream to depth"),
                                               tr("Feed along the reamer axis by (mm), in steps of %1 mm:")
                                                   .arg(feedStep_->value()),
                                               2.0, 0.01, 50.0, 2, &ok);
  if (ok) reamToDepth(depth);
}

void MainWindow::setSteps(double moveMm, double rotateDeg, double feedMm) {
  moveStep_->setValue(moveMm);
  rotateStep_->setValue(rotateDeg);
  feedStep_->setValue(feedMm);
}

double MainWindow::feedStepMm() const { return feedStep_->value(); }

void MainWindow::setKeyBinding(ReamerMove move, const QKeySequence& keys) {
  QAction* a = moveAction(move);
  if (!a) return;
  a->setShortcut(keys);
  if (!persistent_) return;
  for (const MoveInfo& m : reamerMoves())
    if (m.move == move) QSettings().setValue(QString("keys/") + m.id, keys.toString());
}

void MainWindow::loadKeyBindings() {
  if (!persistent_) return;
  QSettings s;
  for (const MoveInfo& m : reamerMoves()) {
    const QString stored = s.value(QString("keys/") + m.id).toString();
    if (!stored.isEmpty()) moveAction(m.move)->setShortcut(QKeySequence(stored));
  }
}

void MainWindow::editKeyBindings() {
  KeyBindingsDialog dialog(this);
  for (const MoveInfo& m : reamerMoves()) dialog.addRow(m.id, tr(m.label), moveAction(m.move)->shortcut(), QKeySequence(m.defaultKey));
  if (dialog.exec() != QDialog::Accepted) return;
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
