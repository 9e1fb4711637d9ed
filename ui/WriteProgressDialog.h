#pragma once
// The window-modal dialog shown while a file is written (or a crash copy read) on a worker: what, how far, and
// Cancel.
// Cancel (the button, Escape or the title bar's close) only asks: the dialog stays, says "Cancelling…", and
// the caller closes it when the worker has stopped, so the window is never free while the file may still
// be replaced.
#include <QDialog>
#include <QEventLoop>
#include <QFutureWatcher>
#include <QtConcurrent/QtConcurrentRun>
#include <atomic>
#include <memory>
#include <utility>

#include "reamsim/ui/ProgressRelay.h"

class QLabel;
class QProgressBar;
class QPushButton;

namespace reamsim::ui {

class WriteProgressDialog : public QDialog {
  Q_OBJECT
 public:
  // `title`: the dialog's (default "Saving"; a crash restore reads with it too).
  WriteProgressDialog(const QString& what, QWidget* parent, const QString& title = {});
  // Read by the worker at each progress check (ProgressRelay.h).
  const std::shared_ptr<std::atomic<bool>>& stopFlag() const { return stop_; }
  void showProgress(double fraction, const QString& stage);
  bool cancelRequested() const { return stop_->load(); }
  // Shows the dialog, runs job(progress) on a worker and waits for it in a local event loop (the window keeps
  // painting, its input blocked), then hides the dialog and returns the job's result. `progress` feeds the dialog
  // and answers false once Cancel was asked. Shown before the worker starts, so that a Cancel at once is heard at
  // the job's first check.
  template <class Job>
  auto runWhileShown(Job job) -> decltype(job(ProgressCallback{}));

 public Q_SLOTS:
  void reject() override;  // Cancel, Escape, close: asks the worker to stop

 private:
  std::shared_ptr<std::atomic<bool>> stop_ = std::make_shared<std::atomic<bool>>(false);
  QLabel* label_ = nullptr;
  QProgressBar* bar_ = nullptr;
  QPushButton* cancel_ = nullptr;
  QString what_;
};

template <class Job>
auto WriteProgressDialog::runWhileShown(Job job) -> decltype(job(ProgressCallback{})) {
  using Result = decltype(job(ProgressCallback{}));
  show();
  const ProgressCallback progress =
      progressRelay(this, [this](double f, const QString& stage) { showProgress(f, stage); }, stop_);
  QEventLoop wait;
  QFutureWatcher<Result> watcher;
  QObject::connect(&watcher, &QFutureWatcher<Result>::finished, &wait, &QEventLoop::quit);
  watcher.setFuture(QtConcurrent::run([job = std::move(job), progress] { return job(progress); }));
  wait.exec();
  hide();
  return watcher.result();
}

}  // namespace reamsim::ui
