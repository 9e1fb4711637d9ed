// The user's work is not lost by a click: closing the window, or opening another bone through the menu,
// with cuts not yet saved asks Save / Discard / Cancel first; Save writes the bone and its cut log, and a
// save that fails (or a cancelled file dialog) keeps the window as it was. The questions are answered
// through the real modal dialogs, as a user would.
#include <QAction>
#include <QDir>
#include <QDockWidget>
#include <QFile>
#include <QFileInfo>
#include <QInputDialog>
#include <QMessageBox>
#include <QStatusBar>
#include <QTableWidget>
#include <QPushButton>
#include <QTemporaryDir>
#include <QThread>
#include <QUndoStack>
#include <QtTest/QTest>

#include "BoneCommands.h"
#include "GuiEnvironment.h"
#include "GuiHelpers.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/CutLogIO.h"

namespace reamsim::ui::test {
namespace {

TEST(GuiUnsavedChanges, AnUnchangedBoneClosesWithoutAsking) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_FALSE(w.isWindowModified());
  EXPECT_TRUE(closeAnswering(w, {}, 0));
}

TEST(GuiUnsavedChanges, CancelKeepsTheWindowAndTheCutsDiscardCloses) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(w.isWindowModified());  // the title's [*]
  const std::uint64_t revision = s.bone()->currentRevision();
  QString text;
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Cancel, &text)}, 1));
  EXPECT_TRUE(text.contains("1 cut")) << text.toStdString();
  EXPECT_TRUE(text.contains("close ReamSim")) << text.toStdString();
  EXPECT_TRUE(w.isVisible());
  EXPECT_EQ(s.bone()->currentRevision(), revision);
  EXPECT_TRUE(w.hasUnsavedChanges());
  // Loading the default case through the menu asks too; Cancel leaves the cut bone.
  {
    ModalAnswers answers({ModalAnswers::button(QMessageBox::Cancel)});
    w.action("load_default")->trigger();
    EXPECT_EQ(answers.seen(), 1);
  }
  EXPECT_EQ(s.bone()->currentRevision(), revision);
  EXPECT_EQ(s.cutsCommitted(), 1u);
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
  EXPECT_FALSE(w.isVisible());
}

TEST(GuiUnsavedChanges, SaveWritesTheBoneAndItsCutLogThenCloses) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QTemporaryDir out;
  const QString path = out.filePath("reamed.ply");
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Save), ModalAnswers::file(path)}, 2))
      << w.lastError().toStdString();
  EXPECT_FALSE(w.isVisible());
  EXPECT_FALSE(w.hasUnsavedChanges());
  ASSERT_TRUE(QFile::exists(path));
  const TriangleMesh saved = readMesh(path.toStdString()).mesh;
  const BoneState& bone = s.bone()->current();
  EXPECT_EQ(saved.triangles.size(), bone.liveTriangleCount());
  EXPECT_NEAR(BoneState::fromMesh(saved).volume(), bone.volume(), 1e-6 * bone.volume());
  QFile csv(out.filePath("reamed.ply.cut_log.csv"));
  ASSERT_TRUE(csv.open(QIODevice::ReadOnly));
  EXPECT_EQ(csv.readAll().count('\n'), 2);  // the header and the one cut
}

// Close, answer Save and give `file`: the save fails with an error naming `named`; the window stays open with
// its unsaved changes.
void expectFailedSaveOnClose(MainWindow& w, const QString& file, const QString& named) {
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Save), ModalAnswers::file(file)}, 2));
  EXPECT_TRUE(w.lastError().contains(named)) << w.lastError().toStdString();
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
  EXPECT_TRUE(w.isVisible());
  EXPECT_TRUE(w.hasUnsavedChanges());
}

TEST(GuiUnsavedChanges, AFailedOrCancelledSaveKeepsTheWindowOpen) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  cutOnce(f.session());
  QTemporaryDir out;
  // A format no writer knows: the save is refused with the writer's message, the window stays.
  expectFailedSaveOnClose(w, out.filePath("bone.unknownformat"), "bone.unknownformat");
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Save), ModalAnswers::cancelFile()}, 2));
  EXPECT_TRUE(w.isVisible());
  EXPECT_TRUE(w.hasUnsavedChanges());
  // The bone written but its cut log not (a folder stands where the log goes): the work is not saved, so the
  // window stays open with unsaved changes and the question comes again.
  ASSERT_TRUE(QDir().mkpath(out.filePath("bone.ply.cut_log.csv")));
  expectFailedSaveOnClose(w, out.filePath("bone.ply"), "bone.ply.cut_log.csv");
  EXPECT_TRUE(QFileInfo::exists(out.filePath("bone.ply")));
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
}

QByteArray contents(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

// The bone is written on a worker behind a window-modal progress dialog (seconds at millions of faces). Its
// Cancel keeps the file that was there and its log, leaves nothing beside them, keeps the changes unsaved,
// and, answered to the close question's Save, keeps the window open.
TEST(GuiUnsavedChanges, ACancelledSaveKeepsTheFileThereAndTheWindowOpen) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QTemporaryDir out;
  const QString path = out.filePath("bone.ply"), log = out.filePath("bone.ply.cut_log.csv");
  ASSERT_TRUE(w.saveBoneAs(path)) << w.lastError().toStdString();
  const QByteArray bone = contents(path), cuts = contents(log);
  ASSERT_FALSE(bone.isEmpty());
  cutOnce(s, 1.0);
  ASSERT_TRUE(w.hasUnsavedChanges());
  {
    CancelProgressOnShow cancel;
    EXPECT_FALSE(w.saveBoneAs(path));
    EXPECT_EQ(cancel.pressed, 1);
  }
  EXPECT_EQ(contents(path), bone);
  EXPECT_EQ(contents(log), cuts);
  EXPECT_EQ(QDir(out.path()).entryList(QDir::Files | QDir::Hidden), (QStringList{"bone.ply", "bone.ply.cut_log.csv", "bone.ply.history.rsj", "bone.ply.landmarks.json"}));
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(w.lastError().isEmpty()) << "a cancel is not an error: " << w.lastError().toStdString();
  {
    CancelProgressOnShow cancel;
    // The close question's Save writes where Save as did, without asking where.
    EXPECT_FALSE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Save)}, 1));
    EXPECT_EQ(cancel.pressed, 1);
  }
  EXPECT_TRUE(w.isVisible());
  EXPECT_EQ(contents(path), bone);
  EXPECT_EQ(QDir(out.path()).entryList(QDir::Files | QDir::Hidden), (QStringList{"bone.ply", "bone.ply.cut_log.csv", "bone.ply.history.rsj", "bone.ply.landmarks.json"}));
  // Let run, the same save writes the cut bone and both cuts.
  ASSERT_TRUE(w.saveBoneAs(path)) << w.lastError().toStdString();
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_EQ(readMesh(path.toStdString()).mesh.triangles.size(), s.bone()->current().liveTriangleCount());
  EXPECT_EQ(contents(log).count('\n'), 3);
  EXPECT_TRUE(closeAnswering(w, {}, 0));
}

// File → Save (Ctrl+S) asks where only the first time; then it, and the close question's Save, write the bone and
// its log where Save as did. Another bone starts without a file (never written over the file it came from).
TEST(GuiUnsavedChanges, SaveWritesWhereSaveAsWroteWithoutAsking) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QTemporaryDir out;
  const QString path = out.filePath("bone.ply"), log = out.filePath("bone.ply.cut_log.csv");
  {
    ModalAnswers answers({ModalAnswers::file(path)});
    w.action("save_again")->trigger();
    EXPECT_EQ(answers.seen(), 1);
  }
  EXPECT_EQ(w.savedPath(), path);
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_EQ(contents(log).count('\n'), 2);
  cutOnce(s, 1.0);
  {
    ModalAnswers answers({});
    w.action("save_again")->trigger();
    EXPECT_EQ(answers.seen(), 0);
  }
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_EQ(readMesh(path.toStdString()).mesh.triangles.size(), s.bone()->current().liveTriangleCount());
  EXPECT_EQ(contents(log).count('\n'), 3);
  cutOnce(s, 1.5);
  ModalAnswers none({});
  ASSERT_TRUE(w.loadDefaultCase());  // another bone (a programmatic load does not ask)
  EXPECT_TRUE(w.savedPath().isEmpty());
  EXPECT_EQ(contents(log).count('\n'), 3);  // the cut not saved was not written by the load
  cutOnce(s);
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Save), ModalAnswers::file(out.filePath("other.ply"))}, 2));
  EXPECT_TRUE(QFileInfo::exists(out.filePath("other.ply.cut_log.csv")));
  EXPECT_EQ(contents(log).count('\n'), 3);
}

// A bone opened while the save is being written (its import ends inside the save's wait) is not the bone in the
// file: the save says so and ties neither the file nor "saved" to the new bone, so Ctrl+S cannot write the new
// bone over the earlier one's file without asking.
TEST(GuiUnsavedChanges, ABoneOpenedDuringASaveIsNotTakenForTheSavedOne) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  const std::size_t cutFaces = s.bone()->current().liveTriangleCount();
  QTemporaryDir out;
  const QString path = out.filePath("bone.ply");
  w.openFile(QString(REAMSIM_TEST_DATA_DIR) + "/good/cube_quads_comments.off", false);
  while (w.importRunning()) QThread::msleep(5);  // done, but its result waits in the event queue
  EXPECT_FALSE(w.saveBoneAs(path));               // the queue runs while the save waits for its worker
  EXPECT_TRUE(w.lastError().contains("another bone has been opened since")) << w.lastError().toStdString();
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
  EXPECT_EQ(s.bone()->current().liveTriangleCount(), 12u);  // the cube is the bone now
  EXPECT_EQ(readMesh(path.toStdString()).mesh.triangles.size(), cutFaces);  // the file holds the cut scapula
  EXPECT_TRUE(w.savedPath().isEmpty());
  ModalAnswers answers({ModalAnswers::cancelFile()});
  w.action("save_again")->trigger();  // asks where
  EXPECT_EQ(answers.seen(), 1);
}

TEST(GuiUnsavedChanges, SavingMarksTheBoneSavedUntilTheHistoryMovesAway) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("bone.ply"))) << w.lastError().toStdString();
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_FALSE(w.isWindowModified());
  w.action("undo")->trigger();  // the bone is no longer the one saved
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(w.isWindowModified());
  w.action("redo")->trigger();  // back to it
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_TRUE(closeAnswering(w, {}, 0));
}

// A note written on a cut in the log dock is work: the title marks it, Save writes it in the cut log beside the
// bone, and closing after a note written since asks again.
TEST(GuiUnsavedChanges, ANoteOnACutIsSavedWithTheLog) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("bone.ply"))) << w.lastError().toStdString();
  ASSERT_FALSE(w.isWindowModified());
  auto* panel = w.findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  const QString note = QString::fromUtf8("rim reached, \"stop\" here\nnext: 2° more retroversion");
  EXPECT_TRUE(annotateRow(w, 0, note));
  QString shown;
  ASSERT_TRUE(QMetaObject::invokeMethod(panel, "noteOfRow", Q_RETURN_ARG(QString, shown), Q_ARG(int, 0)));
  EXPECT_EQ(shown, note);  // the table follows the document
  EXPECT_EQ(s.log()->entries()[0].note, note.toStdString());
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(w.isWindowModified());
  EXPECT_FALSE(annotateRow(w, 1, note));  // no such row
  ASSERT_TRUE(w.saveBoneAs(out.filePath("bone.ply"))) << w.lastError().toStdString();
  EXPECT_FALSE(w.isWindowModified());
  const std::vector<CutLogEntry> saved = readCutLogCsv(out.filePath("bone.ply.cut_log.csv").toStdString());
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_EQ(saved[0].note, note.toStdString());
  // Changed after the save: asked about on close (Cancel keeps the window).
  EXPECT_TRUE(annotateRow(w, 0, "changed"));
  EXPECT_TRUE(w.isWindowModified());
  QString text;
  EXPECT_FALSE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Cancel, &text)}, 1));
  EXPECT_TRUE(text.contains("notes on its cuts have changed")) << text.toStdString();
  EXPECT_FALSE(text.contains("the bone has changed")) << text.toStdString();  // saved: only the note is new
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
}

// Ctrl+Z takes back a note as it takes back a cut, in the order they were made, without touching the bone; a
// note undone back to what was saved is no unsaved change; a note written while an undone cut could be redone is
// written but not recorded (recording it would drop the cut that Redo brings back).
TEST(GuiUnsavedChanges, UndoTakesBackANote) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  QUndoStack& undo = *s.undoStack();
  cutOnce(s);
  cutOnce(s, 0.8);
  const std::uint64_t cut = s.bone()->currentRevision();
  const std::size_t step = s.log()->entries()[0].stepIndex;
  ASSERT_EQ(undo.count(), 2);
  ASSERT_TRUE(annotateRow(w, 0, "first"));
  QTemporaryDir dir;
  ASSERT_TRUE(w.saveBoneAs(dir.filePath("bone.ply"))) << w.lastError().toStdString();
  ASSERT_TRUE(annotateRow(w, 0, "second"));
  ASSERT_EQ(undo.count(), 4);
  EXPECT_EQ(undo.undoText(), QString("Note on step %1").arg(step));
  EXPECT_TRUE(w.hasUnsavedChanges());
  undo.undo();
  EXPECT_EQ(s.log()->entries()[0].note, "first");
  EXPECT_EQ(s.bone()->currentRevision(), cut);  // the bone is as it was
  EXPECT_FALSE(w.hasUnsavedChanges());  // the note as saved
  EXPECT_FALSE(w.isWindowModified());
  undo.undo();
  EXPECT_EQ(s.log()->entries()[0].note, "");
  EXPECT_EQ(s.bone()->currentRevision(), cut);
  EXPECT_TRUE(w.hasUnsavedChanges());
  undo.undo();  // now the second cut
  EXPECT_NE(s.bone()->currentRevision(), cut);
  EXPECT_EQ(s.log()->size(), 2u);  // undo never erases rows
  undo.redo();
  undo.redo();
  EXPECT_EQ(s.log()->entries()[0].note, "first");
  undo.redo();
  EXPECT_EQ(s.log()->entries()[0].note, "second");
  EXPECT_EQ(s.bone()->currentRevision(), cut);
  EXPECT_FALSE(undo.canRedo());

  // A feed runs on while a note is written and undone: neither interrupts the path.
  s.restartPath(ReamSession::PathStart::Changed);  // the undo above interrupted the one before
  const Pose seated = s.reamer()->pose();
  s.runSteps({advancedAlongAxis(seated, 0.1), advancedAlongAxis(seated, 0.2), advancedAlongAxis(seated, 0.3),
              advancedAlongAxis(seated, 0.4)});
  ASSERT_TRUE(s.busy());
  const std::size_t pathBefore = s.path().size();
  ASSERT_TRUE(annotateRow(w, 1, "during the feed"));
  undo.undo();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.path().size(), pathBefore + 4);  // every step ran
  EXPECT_FALSE(s.pathInterrupted());
  EXPECT_EQ(s.log()->entries()[1].note, "");
  const std::uint64_t fed = s.bone()->currentRevision();

  // Notes written on several rows at once (in one batch of the document) are one step to undo.
  const int before = undo.count();
  {
    Document::BatchScope batch(s.document());
    s.log()->setNote(0, "both: a");
    s.log()->setNote(1, "both: b");
  }
  ASSERT_EQ(undo.count(), before + 1);
  EXPECT_EQ(undo.undoText(), "Notes on 2 steps");
  undo.undo();
  EXPECT_EQ(s.log()->entries()[0].note, "second");
  EXPECT_EQ(s.log()->entries()[1].note, "");
  EXPECT_EQ(s.bone()->currentRevision(), fed);
  ASSERT_TRUE(annotateRow(w, 1, "after the undone pair"));  // only notes could be redone: recorded
  EXPECT_EQ(undo.count(), before + 1);
  EXPECT_EQ(undo.undoText(), QString("Note on step %1").arg(s.log()->entries()[1].stepIndex));

  // While a cut could be redone: written, not recorded, and the cut can still be redone.
  undo.setIndex(1);
  ASSERT_NE(s.bone()->currentRevision(), cut);
  const int commands = undo.count();
  ASSERT_TRUE(annotateRow(w, 1, "on the undone cut"));
  EXPECT_EQ(s.log()->entries()[1].note, "on the undone cut");
  EXPECT_EQ(undo.count(), commands);
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("The note is made but Undo cannot take it back"))
      << w.statusBar()->currentMessage().toStdString();
  undo.redo();
  EXPECT_EQ(s.bone()->currentRevision(), cut);  // the second cut is back
  // Redone on, the recorded note on that row would overwrite the one Undo could not record: left as it is.
  undo.setIndex(undo.count());
  EXPECT_EQ(s.log()->entries()[1].note, "on the undone cut");
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("was changed since by an edit Undo could not record"))
      << w.statusBar()->currentMessage().toStdString();
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
}

// A saved bone opens with the cut log saved beside it: its rows and notes in the log, new cuts numbered after
// them and their cumulative volume going on from what had been removed at the save (a cut undone before the
// save not counted). A log beside that is not the one saved with the bone, or cannot be read, is named; the
// bone opens without it, and a save keeps that file aside instead of replacing it.
TEST(GuiUnsavedChanges, ASavedBoneOpensWithItsCutLog) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = s.plan()->poses().front();  // opening a file clears the plan
  const double original = s.bone()->current().volume();
  cutOnce(s);
  cutOnce(s, 0.8);
  ASSERT_TRUE(annotateRow(w, 1, "second cut: rim reached"));
  cutOnce(s, 1.1);
  s.undoStack()->undo();  // the third cut: its row stays in the log, its volume is not removed
  ASSERT_TRUE(s.waitIdle(60000));
  auto* table = w.findChild<QTableWidget*>("LogTable");
  ASSERT_NE(table, nullptr);
  const auto shownUndone = [table](int row) { return table->item(row, 0)->font().italic(); };
  EXPECT_TRUE(shownUndone(2));  // the panel shows the undone cut apart
  EXPECT_FALSE(shownUndone(1));
  s.undoStack()->redo();
  EXPECT_FALSE(shownUndone(2));
  s.undoStack()->undo();
  EXPECT_TRUE(shownUndone(2));
  const double removedAtSave = original - s.bone()->current().volume();
  ASSERT_GT(removedAtSave, 0);
  ASSERT_GT(s.log()->cumulativeMm3(), removedAtSave + 1e-3);  // the undone cut's row says more
  QTemporaryDir dir;
  const QString bonePath = dir.filePath("reamed.ply");
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  const std::vector<std::string> comments = readMesh(bonePath.toStdString()).comments;
  EXPECT_NE(std::find(comments.begin(), comments.end(),
                      "reamsim cut_log 3 " + std::to_string(s.log()->entries().back().timeUnixMs)),
            comments.end());

  w.openFile(bonePath);
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  ASSERT_EQ(s.log()->size(), 3u);
  EXPECT_EQ(s.log()->entries()[1].note, "second cut: rim reached");
  EXPECT_FALSE(w.hasUnsavedChanges());  // the log as saved
  // The third cut was undone before the save: its row says so, and the report marks it.
  EXPECT_FALSE(s.log()->entries()[0].undone);
  EXPECT_FALSE(s.log()->entries()[1].undone);
  EXPECT_TRUE(s.log()->entries()[2].undone);
  EXPECT_TRUE(shownUndone(2));  // and the panel shows it apart
  EXPECT_FALSE(shownUndone(0));
  EXPECT_TRUE(table->item(2, 9)->font().italic());  // its note cell too
  const QString reportPath = dir.filePath("report.html");
  ASSERT_TRUE(w.exportReport(reportPath).isEmpty());
  QFile report(reportPath);
  ASSERT_TRUE(report.open(QIODevice::ReadOnly));
  const QString html = QString::fromUtf8(report.readAll());
  EXPECT_EQ(html.count("(undone)"), 1) << html.toStdString().substr(0, 2000);
  EXPECT_NEAR(s.initialVolumeMm3(), original, 1e-6 * original);
  // One more cut continues the log: numbered after the saved rows, cumulative from what the saved bone lacked.
  const double opened = s.bone()->current().volume();
  cutPastContact(s, start, 0.4);
  ASSERT_EQ(s.log()->size(), 4u);
  const CutLogEntry& next = s.log()->entries().back();
  EXPECT_GT(next.stepIndex, s.log()->entries()[2].stepIndex);
  ASSERT_GT(next.removedMm3, 0);
  EXPECT_NEAR(next.removedMm3, opened - s.bone()->current().volume(), 1e-9 * original);
  EXPECT_NEAR(next.cumulativeMm3, removedAtSave + next.removedMm3, 1e-9 * original);
  EXPECT_TRUE(w.hasUnsavedChanges());
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  ASSERT_EQ(readCutLogCsv(dir.filePath("reamed.ply.cut_log.csv").toStdString()).size(), 4u);

  // Another save's log of the same length put beside the bone is not taken for it.
  const QString logPath = dir.filePath("reamed.ply.cut_log.csv");
  std::vector<CutLogEntry> otherRows = readCutLogCsv(logPath.toStdString());
  otherRows.back().timeUnixMs += 60000;
  const std::string other = cutLogCsv(otherRows);
  writeTextFile(logPath.toStdString(), other);
  w.openFile(bonePath);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains(logPath + ": not the cut log saved with reamed.ply (4 rows"))
      << w.lastError().toStdString();
  EXPECT_EQ(s.log()->size(), 0u);
  // A raw file of the same name (no save of ReamSim's wrote it) takes no log.
  const QString rawPath = dir.filePath("reamed.off");
  writeMesh(s.bone()->current().toMesh(), rawPath.toStdString());
  const QString errorBefore = w.lastError();
  w.openFile(rawPath);
  w.waitImport();
  EXPECT_EQ(w.lastError(), errorBefore);
  EXPECT_EQ(s.log()->size(), 0u);
  // Back to the saved bone: a save keeps the other log aside rather than replacing it.
  w.openFile(bonePath);
  w.waitImport();
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  QFile kept(logPath + ".unreadable");
  ASSERT_TRUE(kept.open(QIODevice::ReadOnly));
  EXPECT_EQ(kept.readAll().toStdString(), other);  // as it was
  EXPECT_TRUE(readCutLogCsv(logPath.toStdString()).empty());  // the log of the bone as now opened: no cuts

  // A log that cannot be read is named with its line; the bone opens without it.
  writeTextFile(logPath.toStdString(), other.substr(0, other.find('\n')) + "\n1,yesterday\n");  // the header, then no row
  w.openFile(bonePath);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains(logPath + ":2: 2 fields")) << w.lastError().toStdString();
  EXPECT_EQ(s.log()->size(), 0u);
  EXPECT_NEAR(s.bone()->current().volume(), BoneState::fromMesh(readMesh(bonePath.toStdString()).mesh).volume(),
              1e-9 * original);  // the bone opened

  // A log the bone was saved with that is gone is named too.
  cutPastContact(s, start, 0.3);
  ASSERT_EQ(s.log()->size(), 1u);
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  ASSERT_TRUE(QFile::remove(logPath));
  w.openFile(bonePath);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains(logPath + ": not found (nor reamed.cut_log.csv); reamed.ply was saved with its cut log there (1 row)"))
      << w.lastError().toStdString();

  // A binary STL's 80-byte header has no room for the removed volume: the log still comes back, and the status bar
  // says where its cumulative volume goes on from.
  cutPastContact(s, start, 0.3);
  ASSERT_EQ(s.log()->size(), 1u);
  QTemporaryDir stlDir;
  const QString stlPath = stlDir.filePath("reamed.stl");
  ASSERT_TRUE(w.saveBoneAs(stlPath)) << w.lastError().toStdString();
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("no room for the volume removed so far"))
      << w.statusBar()->currentMessage().toStdString();
  // Single-precision coordinates: no undo history with it, and the status bar says so.
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("the undo history is not saved with it"))
      << w.statusBar()->currentMessage().toStdString();
  EXPECT_FALSE(QFileInfo::exists(stlPath + ".history.rsj"));
  // A CT bone (a patient frame) with a log of 10,000 rows: the header has no room for the log's record either.
  const std::int64_t t = 1764781234567;
  EXPECT_TRUE(MainWindow::factsLeftOut("x.stl", {PatientFrame::LPS, 12.5, 9999, t, {}, 0}).contains("no room for the volume"));
  EXPECT_TRUE(MainWindow::factsLeftOut("x.stl", {PatientFrame::LPS, 12.5, 10000, t, {}, 0}).contains("no room to record the cut log"));
  EXPECT_TRUE(MainWindow::factsLeftOut("x.ply", {PatientFrame::LPS, 12.5, 100000, t, {}, 0}).isEmpty());
  const QString errorBeforeStl = w.lastError();
  w.openFile(stlPath);
  w.waitImport();
  EXPECT_EQ(w.lastError(), errorBeforeStl);  // nothing refused
  EXPECT_EQ(s.log()->size(), 1u);
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("with its cut log (1 step; the file has no room for the volume "
                                                        "removed at the save"))
      << w.statusBar()->currentMessage().toStdString();
}

// The log is named after the bone file's whole name (as its landmarks are): the same bone saved as NAME.ply and,
// later cut further, as NAME.obj keeps both logs, and each reopens with its own. A log an earlier save wrote
// under NAME.cut_log.csv still comes back, and a save does not write over it.
TEST(GuiUnsavedChanges, BonesOfOneNameInTwoFormatsKeepTheirOwnCutLogs) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = s.plan()->poses().front();  // opening a file clears the plan
  cutOnce(s);
  QTemporaryDir dir;
  const QString ply = dir.filePath("glenoid.ply"), obj = dir.filePath("glenoid.obj");
  ASSERT_TRUE(w.saveBoneAs(ply)) << w.lastError().toStdString();
  cutOnce(s, 0.9);
  ASSERT_TRUE(w.saveBoneAs(obj)) << w.lastError().toStdString();
  EXPECT_EQ(readCutLogCsv((ply + ".cut_log.csv").toStdString()).size(), 1u);
  EXPECT_EQ(readCutLogCsv((obj + ".cut_log.csv").toStdString()).size(), 2u);
  for (const auto& [path, rows] : {std::pair{ply, 1u}, std::pair{obj, 2u}}) {
    w.openFile(path);
    w.waitImport();
    EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
    EXPECT_EQ(s.log()->size(), rows) << path.toStdString();
    EXPECT_FALSE(w.hasUnsavedChanges());
  }

  // As an earlier save left it: the log under the bone's base name.
  const QString earlier = dir.filePath("glenoid.cut_log.csv");
  ASSERT_TRUE(QFile::rename(ply + ".cut_log.csv", earlier));
  const QByteArray earlierLog = contents(earlier);
  w.openFile(ply);
  w.waitImport();
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  ASSERT_EQ(s.log()->size(), 1u);
  cutPastContact(s, start, 0.4);
  ASSERT_EQ(s.log()->size(), 2u);
  ASSERT_TRUE(w.saveBoneAs(ply)) << w.lastError().toStdString();
  EXPECT_EQ(readCutLogCsv((ply + ".cut_log.csv").toStdString()).size(), 2u);
  EXPECT_EQ(contents(earlier), earlierLog);  // not written over
  w.openFile(ply);  // the log of its own name comes first
  w.waitImport();
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_EQ(s.log()->size(), 2u);
}

// The facts a save writes into the bone file's comments read back as written; a fact that does not parse whole, or
// an undo history of fewer than two states or with its bone past its end, is no fact.
TEST(BoneFileFacts, ReadBackAsWrittenAndNothingHalfParsed) {
  BoneFileFacts facts{PatientFrame::RAS, 1234.5678901234567, 12, 1764781234567, 5, 3};
  const BoneFileFacts back = factsFromComments(factComments(facts));
  EXPECT_EQ(back.frame, PatientFrame::RAS);
  EXPECT_EQ(back.removedMm3, facts.removedMm3);
  EXPECT_EQ(back.cutLogRows, facts.cutLogRows);
  EXPECT_EQ(back.cutLogLastMs, facts.cutLogLastMs);
  EXPECT_EQ(back.historyStates, std::optional<std::size_t>(5));
  EXPECT_EQ(back.historyCursor, 3u);
  for (const char* bad : {"reamsim undo_history 5", "reamsim undo_history 5 5", "reamsim undo_history 1 0",
                          "reamsim undo_history 5 2x", "reamsim undo_history -3 1"})
    EXPECT_FALSE(factsFromComments({bad}).historyStates) << bad;
  EXPECT_TRUE(factComments(BoneFileFacts{}).empty());
}

// A save writes the bone's undo history beside it (NAME.ply.history.rsj): reopened, the bone undoes the cuts made
// before the save and redoes those undone before it, the log's undone marks follow, and undone back to the saved
// state it is as saved. A history that is missing or damaged is named; the bone opens without it.
TEST(GuiUnsavedChanges, AReopenedBoneUndoesAndRedoesItsCuts) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = s.plan()->poses().front();  // opening a file clears the plan
  const double original = s.bone()->current().volume();
  std::vector<double> volumes{original};
  for (double depth : {0.5, 0.9, 1.3}) {
    cutOnce(s, depth);
    volumes.push_back(s.bone()->current().volume());
  }
  s.undoStack()->undo();  // the third cut: Redo can bring it back
  ASSERT_TRUE(s.waitIdle(60000));
  QTemporaryDir dir;
  const QString bonePath = dir.filePath("reamed.ply");
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  const QString historyPath = bonePath + ".history.rsj";
  ASSERT_TRUE(QFileInfo::exists(historyPath));

  w.openFile(bonePath);
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("and its undo history (3 steps)"))
      << w.statusBar()->currentMessage().toStdString();
  QUndoStack& undo = *s.undoStack();
  ASSERT_EQ(undo.count(), 3);
  EXPECT_EQ(undo.index(), 2);
  EXPECT_TRUE(undo.canRedo());
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_NEAR(s.bone()->current().volume(), volumes[2], 1e-9 * original);
  ASSERT_EQ(s.log()->size(), 3u);
  const auto undoneRows = [&s] {
    std::vector<bool> out;
    for (const CutLogEntry& e : withUndoneMarked(s.log()->entries(), s.bone()->history())) out.push_back(e.undone);
    return out;
  };
  EXPECT_EQ(undoneRows(), (std::vector<bool>{false, false, true}));

  w.action("undo")->trigger();
  w.action("undo")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_NEAR(s.bone()->current().volume(), volumes[0], 1e-9 * original);  // the bone as first opened
  EXPECT_FALSE(undo.canUndo());
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_EQ(undoneRows(), (std::vector<bool>{true, true, true}));
  for (int k = 0; k < 3; ++k) w.action("redo")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_NEAR(s.bone()->current().volume(), volumes[3], 1e-9 * original);  // the cut undone before the save
  EXPECT_EQ(undoneRows(), (std::vector<bool>{false, false, false}));
  w.action("undo")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(w.hasUnsavedChanges());  // back at the saved state
  // A new cut from there: its cumulative volume counts from the bone first opened.
  cutPastContact(s, start, 0.4);
  ASSERT_EQ(s.log()->size(), 4u);
  const CutLogEntry& next = s.log()->entries().back();
  EXPECT_NEAR(next.cumulativeMm3, original - s.bone()->current().volume(), 1e-9 * original);

  // Missing, then damaged (a record cut short): named, and the bone opens without it. Saved again first, to a
  // history readable by its owner only: the new one keeps that.
  ASSERT_TRUE(QFile::setPermissions(historyPath, QFile::ReadOwner | QFile::WriteOwner));
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  EXPECT_EQ(QFile::permissions(historyPath) & (QFile::ReadGroup | QFile::ReadOther), QFile::Permissions());
  // A history kept elsewhere through a link: the link stays, its target takes the new history.
  ASSERT_TRUE(QDir(dir.path()).mkdir("kept"));
  const QString elsewhere = dir.filePath("kept/history.rsj");
  ASSERT_TRUE(QFile::rename(historyPath, elsewhere));
  ASSERT_TRUE(QFile::link(elsewhere, historyPath));
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  EXPECT_TRUE(QFileInfo(historyPath).isSymLink());
  EXPECT_EQ(journalRevisions(elsewhere.toStdString()).size(), s.bone()->history().size());
  ASSERT_TRUE(QFile::rename(historyPath, historyPath + ".kept"));
  w.openFile(bonePath);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains(historyPath + ": not found")) << w.lastError().toStdString();
  EXPECT_EQ(undo.count(), 0);
  EXPECT_EQ(s.log()->size(), 4u);  // the log still comes back
  EXPECT_FALSE(w.hasUnsavedChanges());
  ASSERT_TRUE(QFile::rename(historyPath + ".kept", historyPath));
  ASSERT_TRUE(QFile::resize(historyPath, QFileInfo(historyPath).size() - 100));
  w.openFile(bonePath);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains("not the undo history saved with the bone (3 states; saved: 4)"))
      << w.lastError().toStdString();
  EXPECT_EQ(undo.count(), 0);
  EXPECT_NEAR(s.bone()->current().volume(), BoneState::fromMesh(readMesh(bonePath.toStdString()).mesh).volume(),
              1e-9 * original);
  // The next save keeps the damaged file aside: it is the user's to look at, never removed or written over.
  const QByteArray damaged = contents(historyPath);
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  EXPECT_EQ(contents(historyPath + ".unreadable"), damaged);
  EXPECT_FALSE(QFileInfo::exists(historyPath));
}

// Redo states the undo stack has dropped (another edit pushed while cuts were undone) are not saved: reopened,
// Redo cannot bring back a cut the session could not.
TEST(GuiUnsavedChanges, ASaveLeavesOutCutsTheStackCanNoLongerRedo) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  cutOnce(s, 0.9);
  s.undoStack()->undo();
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_EQ(s.bone()->history().size(), 3u);  // the history keeps the undone cut...
  auto node = std::make_unique<BoneNode>("beside");
  BoneContent content;
  content.name = "beside";
  content.history = BoneHistory(s.bone()->current(), "test");
  node->swapContent(content);
  std::vector<std::unique_ptr<BoneNode>> nodes;
  nodes.push_back(std::move(node));
  s.undoStack()->push(new OtherBonesCommand(s.document(), std::move(nodes), "Add beside"));
  ASSERT_FALSE(s.undoStack()->canRedo());  // ...the stack cannot redo it any more
  EXPECT_EQ(s.bone()->history().size(), 3u);
  QTemporaryDir dir;
  const QString bonePath = dir.filePath("bone.ply");
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  const std::vector<std::string> comments = readMesh(bonePath.toStdString()).comments;
  EXPECT_NE(std::find(comments.begin(), comments.end(), "reamsim undo_history 2 1"), comments.end());
  w.openFile(bonePath);
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_EQ(s.undoStack()->count(), 1);
  EXPECT_FALSE(s.undoStack()->canRedo());
}

// As a user writes one: a double-click on the cut's row opens the note dialog with the note so far; OK writes
// it, Cancel leaves it.
TEST(GuiUnsavedChanges, ADoubleClickOnACutWritesItsNote) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);
  cutOnce(s, 0.7);
  auto* panel = w.findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  auto* table = panel->findChild<QTableWidget*>("LogTable");
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rowCount(), 2);
  const auto writeNote = [](const QString& note, QString* shown) {
    return [note, shown](QWidget* m) {
      auto* dialog = qobject_cast<QInputDialog*>(m);
      ASSERT_NE(dialog, nullptr) << m->metaObject()->className();
      *shown = dialog->textValue();
      if (note.isNull()) return dialog->reject();
      dialog->setTextValue(note);
      dialog->accept();
    };
  };
  const auto doubleClickRow = [&](int row) {
    table->scrollToItem(table->item(row, 0));
    const QRect cell = table->visualItemRect(table->item(row, 0));
    // A double-click is a press and release, then the double-click event (QTest sends only the last).
    QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, cell.center());
    QTest::mouseDClick(table->viewport(), Qt::LeftButton, {}, cell.center());
  };
  QString before;
  {
    ModalAnswers answers({writeNote("second pass\ndeeper", &before)});
    doubleClickRow(1);
    EXPECT_EQ(answers.seen(), 1);
  }
  EXPECT_TRUE(before.isEmpty());
  EXPECT_EQ(s.log()->entries()[1].note, "second pass\ndeeper");
  EXPECT_EQ(s.log()->entries()[0].note, "");
  EXPECT_EQ(table->item(1, table->columnCount() - 1)->text(), "second pass\ndeeper");
  {
    ModalAnswers answers({writeNote(QString(), &before)});  // Cancel
    doubleClickRow(1);
    EXPECT_EQ(answers.seen(), 1);
  }
  EXPECT_EQ(before, "second pass\ndeeper");  // the dialog starts from the note so far
  EXPECT_EQ(s.log()->entries()[1].note, "second pass\ndeeper");
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
}

}  // namespace
}  // namespace reamsim::ui::test
