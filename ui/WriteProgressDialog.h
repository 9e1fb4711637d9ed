#pragma once
// The window-modal dialog shown while a file is written (or a crash copy read) on a worker: what, how far, and
// Cancel.
// Cancel (the button, Escape or the title bar's close) only asks: the dialog stays, says "Cancelling…", and
// the caller closes it when the worker has stopped, so the window is never free while the file may still
// be replaced.
#include <QDialog>
#include <atomic>
#include <memory>

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

 public Q_SLOTS:
  void reject() override;  // Cancel, Escape, close: asks the worker to stop

 private:
  std::shared_ptr<std::atomic<bool>> stop_ = std::make_shared<std::atomic<bool>>(false);
  QLabel* label_ = nullptr;
  QProgressBar* bar_ = nullptr;
  QPushButton* cancel_ = nullptr;
  QString what_;
};

}  // namespace reamsim::ui
