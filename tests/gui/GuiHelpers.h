#pragma once
// GUI test helpers: answering the real modal dialogs as a user would, and making a cut.
#include <gtest/gtest.h>

#include <QAbstractButton>
#include <QApplication>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QMessageBox>
#include <QPushButton>
#include <QTimer>
#include <deque>
#include <functional>

#include "ReamSession.h"
#include "reamsim/ream/Approach.h"

namespace reamsim::ui::test {

// Answers the modal dialogs as they open, one answer each, in order; counts those it saw.
class ModalAnswers {
 public:
  using Answer = std::function<void(QWidget*)>;
  explicit ModalAnswers(std::deque<Answer> answers) : answers_(std::move(answers)) {
    timer_.setInterval(20);
    QObject::connect(&timer_, &QTimer::timeout, [this] {
      QWidget* modal = QApplication::activeModalWidget();
      // A file being written shows a window-modal progress dialog for as long as that takes: not a question.
      if (modal && modal->objectName() == "WriteProgressDialog") return;
      if (!modal) last_ = nullptr;  // the next dialog may reuse the last one's address
      if (!modal || modal == last_) return;
      last_ = modal;
      ++seen_;
      if (answers_.empty()) return;
      Answer a = std::move(answers_.front());
      answers_.pop_front();
      a(modal);
    });
    timer_.start();
  }
  int seen() const { return seen_; }

  static Answer button(QMessageBox::StandardButton which, QString* text = nullptr) {
    return [which, text](QWidget* w) {
      auto* box = qobject_cast<QMessageBox*>(w);
      ASSERT_NE(box, nullptr) << "expected the unsaved-changes question, got " << w->metaObject()->className();
      EXPECT_EQ(box->objectName(), "UnsavedChangesDialog");
      if (text) *text = box->text() + "\n" + box->informativeText();
      box->button(which)->click();
    };
  }
  // A message box `dialogName`: its button labelled `buttonText` (`text`, when given, gets the box's text).
  static Answer click(const QString& dialogName, const QString& buttonText, QString* text = nullptr) {
    return [dialogName, buttonText, text](QWidget* w) {
      auto* box = qobject_cast<QMessageBox*>(w);
      ASSERT_NE(box, nullptr) << "expected " << dialogName.toStdString() << ", got " << w->metaObject()->className();
      EXPECT_EQ(box->objectName(), dialogName);
      if (text) *text = box->text();
      for (QAbstractButton* b : box->buttons())
        if (b->text().remove('&') == buttonText) return b->click();
      ADD_FAILURE() << "no button " << buttonText.toStdString() << " in " << dialogName.toStdString();
      box->reject();
    };
  }
  static Answer file(const QString& path) {
    return [path](QWidget* w) {
      auto* dialog = qobject_cast<QFileDialog*>(w);
      ASSERT_NE(dialog, nullptr) << "expected the save dialog, got " << w->metaObject()->className();
      // selectFile sets the name box only while it has no keyboard focus (Qt 5.15), and the dialog takes a path
      // in another folder once its file system model has been there (a worker thread): until then the box may
      // still hold the proposed "bone.ply", and accepting would ask whether to replace that file (seen once
      // under load: a nested question nobody answers).
      if (QWidget* focused = dialog->focusWidget()) focused->clearFocus();
      dialog->selectFile(path);
      QElapsedTimer waited;
      waited.start();
      while (dialog->selectedFiles().value(0) != path && waited.elapsed() < 5000) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
        dialog->selectFile(path);
      }
      if (dialog->selectedFiles().value(0) != path) {
        ADD_FAILURE() << "the save dialog does not take " << path.toStdString() << ": it has "
                      << dialog->selectedFiles().value(0).toStdString();
        return dialog->reject();
      }
      static_cast<QDialog*>(dialog)->accept();  // as the dialog's Save button (QFileDialog's own is protected)
    };
  }
  static Answer cancelFile() {
    return [](QWidget* w) {
      auto* dialog = qobject_cast<QFileDialog*>(w);
      ASSERT_NE(dialog, nullptr);
      dialog->reject();
    };
  }

 private:
  std::deque<Answer> answers_;
  QTimer timer_;
  QWidget* last_ = nullptr;
  int seen_ = 0;
};

// Closes `w`, answering the dialogs the close opens; true when it closed. Expects `dialogs` of them.
inline bool closeAnswering(QWidget& w, std::deque<ModalAnswers::Answer> answers, int dialogs) {
  ModalAnswers modal(std::move(answers));
  const bool closed = w.close();
  EXPECT_EQ(modal.seen(), dialogs);
  return closed;
}

// The same pose to the last bit (a pose put back, not recomputed).
inline bool samePose(const Pose& a, const Pose& b) {
  return a.tip.x == b.tip.x && a.tip.y == b.tip.y && a.tip.z == b.tip.z && a.axis.x == b.axis.x && a.axis.y == b.axis.y &&
         a.axis.z == b.axis.z && a.rollDeg == b.rollDeg;
}

// One more cut: the reamer placed `depthMm` past where it first touches the glenoid from the default plan's
// start (deeper than any cut before, or nothing is cut).
inline void cutOnce(ReamSession& s, double depthMm = 0.5) {
  const std::size_t before = s.cutsCommitted();
  const Pose start = s.plan()->poses().front();
  const double approach = *advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), start, 100);
  s.moveReamer(advancedAlongAxis(start, approach + depthMm));
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_EQ(s.cutsCommitted(), before + 1);
}

// The reamer placed `depthMm` past where it first touches the bone along `start`'s axis (a pose kept from the
// default plan before opening a file cleared the plan), and the step awaited: one more cut when deeper than any
// before.
inline void cutPastContact(ReamSession& s, const Pose& start, double depthMm) {
  const double approach = *advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), start, 100);
  s.moveReamer(advancedAlongAxis(start, approach + depthMm));
  ASSERT_TRUE(s.waitIdle(60000));
}

// Presses Cancel on every WriteProgressDialog (a save's, a crash restore's) as it appears, before its worker's
// first check: counts the presses.
class CancelProgressOnShow : public QObject {
 public:
  CancelProgressOnShow() { qApp->installEventFilter(this); }
  ~CancelProgressOnShow() override { qApp->removeEventFilter(this); }
  int pressed = 0;

 protected:
  bool eventFilter(QObject* o, QEvent* e) override {
    if (e->type() == QEvent::Show && o->objectName() == "WriteProgressDialog") {
      auto* cancel = o->findChild<QPushButton*>("WriteCancelButton");
      EXPECT_NE(cancel, nullptr);
      if (cancel) cancel->click(), ++pressed;
    }
    return false;
  }
};

// Writes `note` on the log dock's row `row` as its Note… does (LogPanel::annotateRow, a slot of the plugin's
// dock); false when the dock has no such row.
inline bool annotateRow(QWidget& window, int row, const QString& note) {
  QObject* panel = window.findChild<QObject*>("LogPanel");
  bool annotated = false;
  EXPECT_NE(panel, nullptr);
  if (panel) {
    EXPECT_TRUE(QMetaObject::invokeMethod(panel, "annotateRow", Q_RETURN_ARG(bool, annotated), Q_ARG(int, row),
                                          Q_ARG(QString, note)));
  }
  return annotated;
}

}  // namespace reamsim::ui::test
