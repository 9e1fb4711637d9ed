// Crash recovery: while cuts are unsaved a copy of the bone and its cut log is kept on disk (written off the
// UI thread a moment after each change); a save or a normal close removes it; a copy left behind (the window
// went away without a close, as in a crash) is offered by the next window, which restores the bone exactly
// or deletes the copy, as the user answers; a second window does not touch the first one's copy.
#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStatusBar>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest/QTest>

#include "GuiEnvironment.h"
#include "reamsim/ream/ScapularFrame.h"
#include "BoneCommands.h"
#include "GuiHelpers.h"
#include "OtherBonesLayer.h"
#include "RecoveryFiles.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim::ui::test {
namespace {

int lines(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? static_cast<int>(f.readAll().count('\n')) : -1;
}

// The window's copy, once its writer has caught up with the last change.
std::optional<RecoveredBone> settledCopy(MainWindow& w) {
  QTest::qWait(50);  // the timer (0 ms here) starts the writer from the event loop
  EXPECT_TRUE(QTest::qWaitFor([&] { return !w.recoveryWriteRunning(); }, 30000));
  QTest::qWait(50);
  return w.recovery()->found();
}

// One cut in a window that then goes away without a close (as in a crash), its copy settled; the bone's volume.
double crashAfterOneCut(const QTemporaryDir& dir) {
  GuiFixture crashed;
  crashed.window->enableRecovery(dir.filePath("recovery"), 0);
  cutOnce(crashed.session());
  EXPECT_TRUE(settledCopy(*crashed.window));
  return crashed.session().bone()->current().volume();
}

// Restores the copy in `w` (answering Restore) when part of it is damaged: waits for the message that says so.
void restoreExpectingAMessage(MainWindow& w, const QTemporaryDir& dir) {
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  w.enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !w.lastError().isEmpty(); }, 30000));
  EXPECT_TRUE(w.windowTitle().contains("(recovered)"));
}

// Restores the copy in `w` (answering Restore) and waits for the title to say so.
void restoreCopy(MainWindow& w, const QTemporaryDir& dir) {
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  w.enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w.windowTitle().contains("(recovered)"); }, 30000)) << w.lastError().toStdString();
  EXPECT_EQ(answers.seen(), 1);
}

// The bone's shape 200 mm along x: a second bone that does not meet the first.
TriangleMesh movedAside(const BoneState& bone) {
  TriangleMesh m = bone.toMesh();
  for (Vec3& v : m.vertices) v.x += 200;
  return m;
}

// Restores the copy in `f`'s window (answering Restore); the one bone restored beside the restored bone, or null.
const BoneNode* restoreWithOneBoneBeside(GuiFixture& f, const QTemporaryDir& dir) {
  MainWindow& w = *f.window;
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  w.enableRecovery(dir.filePath("recovery"), 0);
  EXPECT_TRUE(QTest::qWaitFor([&] { return w.windowTitle().contains("(recovered)"); }, 30000)) << w.lastError().toStdString();
  QTest::qWait(50);
  const std::vector<BoneNode*> bones = f.session().document().nodesOf<BoneNode>();
  EXPECT_EQ(bones.size(), 2u);
  if (bones.size() != 2) return nullptr;
  return bones[0] == f.session().bone() ? bones[1] : bones[0];
}

// Revisions restart in every process: a journal's name carries a token of the window that writes it, so a window
// never appends to (or reads as its own) a journal another process left with the same first revision.
TEST(GuiRecovery, EachWindowNamesItsJournalsApart) {
  QTemporaryDir dir;
  const RecoveryFiles first(dir.filePath("recovery")), second(dir.filePath("recovery"));
  EXPECT_NE(first.historyPath(7), second.historyPath(7));
  EXPECT_EQ(first.historyPath(7), first.historyPath(7));
}

TEST(GuiRecovery, UnsavedCutsAreCopiedASaveOrACloseRemovesTheCopy) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;
  MainWindow& w = *f.window;
  w.enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_NE(w.recovery(), nullptr);
  EXPECT_TRUE(w.recovery()->owns());
  EXPECT_FALSE(settledCopy(w));  // nothing unsaved

  cutOnce(f.session());
  std::optional<RecoveredBone> copy = settledCopy(w);
  ASSERT_TRUE(copy);
  EXPECT_EQ(copy->cuts, 1);
  EXPECT_EQ(copy->name, "default scapula");
  const BoneState& bone = f.session().bone()->current();
  const TriangleMesh copied = readMesh(copy->bonePath.toStdString()).mesh;
  EXPECT_EQ(copied.triangles.size(), bone.liveTriangleCount());
  EXPECT_NEAR(BoneState::fromMesh(copied).volume(), bone.volume(), 1e-9 * bone.volume());
  EXPECT_EQ(lines(copy->logPath), 2);  // header and the cut

  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("bone.ply")));
  EXPECT_FALSE(settledCopy(w));  // saved: nothing to recover

  cutOnce(f.session(), 1.0);
  copy = settledCopy(w);
  ASSERT_TRUE(copy);
  EXPECT_EQ(copy->cuts, 2);  // the log since the bone was opened
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
  EXPECT_FALSE(RecoveryFiles(dir.filePath("recovery")).found());  // a normal close leaves no copy
}

// A note written on a cut after the bone was saved is unsaved work of its own: copied, and back after a crash.
TEST(GuiRecovery, ANoteWrittenAfterASaveIsCopiedAndComesBack) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir, out;
  const std::string note = "left at 1.5 mm: sclerotic bone";
  {
    GuiFixture crashed;
    crashed.window->enableRecovery(dir.filePath("recovery"), 0);
    cutOnce(crashed.session());
    ASSERT_TRUE(crashed.window->saveBoneAs(out.filePath("bone.ply")));
    EXPECT_FALSE(settledCopy(*crashed.window));  // saved: nothing to recover
    crashed.session().log()->setNote(0, note);   // as the log dock writes it
    const std::optional<RecoveredBone> copy = settledCopy(*crashed.window);
    ASSERT_TRUE(copy);
    const std::vector<CutLogEntry> rows = readCutLogCsv(copy->logPath.toStdString());
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0].note, note);
  }  // gone without a close, as in a crash
  GuiFixture f;
  restoreCopy(*f.window, dir);
  ASSERT_EQ(f.session().log()->size(), 1u);
  EXPECT_EQ(f.session().log()->entries()[0].note, note);
}

// The undo history's journal cannot be written (here a folder stands where the file goes; a full disk does the
// same): the copy is still written with the bone and its log, the message says the history is not in it, and
// after a crash the bone comes back, with its history from the copy's state on.
TEST(GuiRecovery, AJournalThatCannotBeWrittenLeavesACopyWithoutTheHistory) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  double volume = 0;
  {
    GuiFixture crashed;
    MainWindow& w = *crashed.window;
    w.enableRecovery(dir.filePath("recovery"), 0);
    const std::uint64_t first = crashed.session().bone()->history().entries().front().revision;
    ASSERT_TRUE(QDir().mkpath(w.recovery()->historyPath(first)));
    cutOnce(crashed.session());
    const std::optional<RecoveredBone> copy = settledCopy(w);
    ASSERT_TRUE(copy);
    EXPECT_TRUE(copy->historyRevisions.empty());
    EXPECT_TRUE(w.statusBar()->currentMessage().contains("the undo history is not in the copy"))
        << w.statusBar()->currentMessage().toStdString();
    EXPECT_TRUE(w.statusBar()->currentMessage().contains(w.recovery()->historyPath(first)))
        << w.statusBar()->currentMessage().toStdString();
    volume = crashed.session().bone()->current().volume();
  }  // gone without a close, as in a crash
  GuiFixture f;
  MainWindow& w = *f.window;
  restoreCopy(w, dir);
  EXPECT_NEAR(f.session().bone()->current().volume(), volume, 1e-6 * volume);
  EXPECT_EQ(f.session().log()->size(), 1u);
  EXPECT_TRUE(w.hasUnsavedChanges());
}

TEST(GuiRecovery, ACopyLeftBehindIsOfferedAndRestoresTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  std::size_t faces = 0, openedFaces = 0, secondCutFaces = 0;
  double volume = 0, removed = 0, openedVolume = 0, secondCutVolume = 0;
  QString undoText;
  std::vector<CutLogEntry> logged;
  std::vector<Pose> plan;
  ScapulaLandmarks landmarks;
  {
    GuiFixture crashed;
    crashed.window->enableRecovery(dir.filePath("recovery"), 0);
    openedFaces = crashed.session().bone()->current().liveTriangleCount();
    openedVolume = crashed.session().bone()->current().volume();
    ASSERT_TRUE(crashed.window->chooseReamer("glenoid-40-R32"));  // restored with the bone
    cutOnce(crashed.session());
    cutOnce(crashed.session(), 1.0);
    secondCutFaces = crashed.session().bone()->current().liveTriangleCount();
    secondCutVolume = crashed.session().bone()->current().volume();
    crashed.window->action("undo")->trigger();  // the log keeps both rows; the bone is back after the first
    ASSERT_TRUE(crashed.session().waitIdle(60000));
    ASSERT_TRUE(settledCopy(*crashed.window));
    // A landmark placed again after the last cut: the copy follows it (the user's work, as the cuts are).
    Vec3 centre = *crashed.session().bone()->landmarks()[ScapulaLandmark::GlenoidCentre];
    centre.x += 0.75;
    crashed.session().bone()->setLandmark(ScapulaLandmark::GlenoidCentre, centre);
    crashed.session().bone()->setPlannedAxis(Pose{centre, {0, 0, -1}, 0});
    landmarks = crashed.session().bone()->landmarks();
    const std::optional<RecoveredBone> copy = settledCopy(*crashed.window);
    ASSERT_TRUE(copy);
    EXPECT_EQ(parseLandmarksJson(copy->landmarksJson.toStdString(), "copy"), landmarks);  // the moved centre
    EXPECT_FALSE(copy->historyPath.isEmpty());  // the undo history: three states, at the second
    EXPECT_EQ(copy->historyRevisions.size(), 3u);
    EXPECT_EQ(copy->historyCursor, 1u);
    faces = crashed.session().bone()->current().liveTriangleCount();
    volume = crashed.session().bone()->current().volume();
    removed = crashed.session().initialVolumeMm3() - volume;
    logged = crashed.session().log()->entries();
    plan = crashed.session().plan()->poses();
  }  // gone without a close
  ASSERT_EQ(logged.size(), 2u);
  ASSERT_LT(removed, logged.back().cumulativeMm3);  // the undone cut is not counted
  GuiFixture f;
  MainWindow& w = *f.window;
  ASSERT_FALSE(w.hasUnsavedChanges());
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  w.enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w.windowTitle().contains("(recovered)"); }, 30000)) << w.lastError().toStdString();
  EXPECT_EQ(answers.seen(), 1);
  const BoneState& bone = f.session().bone()->current();
  EXPECT_EQ(bone.liveTriangleCount(), faces);
  EXPECT_NEAR(bone.volume(), volume, 1e-9 * volume);
  EXPECT_TRUE(f.session().canCut()) << f.session().cuttingStatus().toStdString();
  EXPECT_TRUE(w.hasUnsavedChanges());  // kept nowhere but in the recovery copy
  // The log up to the crash is back in the log panel's model, row for row (no file is left beside it).
  EXPECT_TRUE(w.recoveredLogPath().isEmpty());
  const std::vector<CutLogEntry>& restored = f.session().log()->entries();
  ASSERT_EQ(restored.size(), logged.size());
  for (std::size_t i = 0; i < logged.size(); ++i) {
    EXPECT_EQ(restored[i].stepIndex, logged[i].stepIndex);
    EXPECT_EQ(restored[i].timeUnixMs, logged[i].timeUnixMs);
    EXPECT_EQ(restored[i].faces, logged[i].faces);
    EXPECT_NEAR(restored[i].removedMm3, logged[i].removedMm3, 1e-8 * logged[i].removedMm3);
    EXPECT_NEAR(restored[i].cumulativeMm3, logged[i].cumulativeMm3, 1e-8 * logged[i].cumulativeMm3);
    EXPECT_EQ(restored[i].reamer, logged[i].reamer);
    // The crashed session's revisions, mapped state by state to the adopted history's.
    EXPECT_EQ(restored[i].boneStateId, f.session().bone()->history().entries()[i + 1].revision);
  }
  auto* table = w.findChild<QTableWidget*>("LogTable");  // what the user sees
  ASSERT_NE(table, nullptr);
  QTest::qWait(50);
  EXPECT_EQ(table->rowCount(), 2);
  const QString status = w.statusBar()->currentMessage();
  EXPECT_TRUE(status.contains("cut log (2 steps)")) << status.toStdString();
  EXPECT_TRUE(status.contains("undo history (2 steps)")) << status.toStdString() << w.lastError().toStdString();
  EXPECT_EQ(f.session().reamer()->spec().name, "glenoid-40-R32");
  EXPECT_EQ(f.session().bone()->landmarks(), landmarks);  // to the bit: the copy keeps every digit
  ASSERT_TRUE(f.session().bone()->plannedAxis());
  EXPECT_EQ(f.session().bone()->plannedAxis()->tip, *landmarks[ScapulaLandmark::GlenoidCentre]);
  // The undo history is back as it was at the crash: the bone as opened, the first cut (here), the undone second.
  EXPECT_EQ(f.session().bone()->history().size(), 3u);
  EXPECT_EQ(f.session().bone()->history().cursor(), 1u);
  ASSERT_EQ(f.session().undoStack()->count(), 2);
  EXPECT_EQ(f.session().undoStack()->index(), 1);
  EXPECT_TRUE(f.session().undoStack()->text(0).contains("before the crash")) << f.session().undoStack()->text(0).toStdString();
  w.action("redo")->trigger();  // the cut undone before the crash
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), secondCutFaces);
  EXPECT_NEAR(f.session().bone()->current().volume(), secondCutVolume, 1e-9 * secondCutVolume);
  w.action("undo")->trigger();
  w.action("undo")->trigger();  // back to the bone as opened
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), openedFaces);
  EXPECT_NEAR(f.session().bone()->current().volume(), openedVolume, 1e-9 * openedVolume);
  EXPECT_NEAR(f.session().initialVolumeMm3(), openedVolume, 1e-9 * openedVolume);
  EXPECT_TRUE(w.hasUnsavedChanges());
  w.action("redo")->trigger();  // the restored bone again
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), faces);
  EXPECT_NEAR(f.session().initialVolumeMm3() - f.session().bone()->current().volume(), removed, 1e-6 * removed);
  // The next cut continues the log: its step number after the last, its cumulative volume from what had
  // been removed at the crash (the undone cut not counted).
  f.session().plan()->setPoses(plan);
  cutOnce(f.session(), 2.0);
  ASSERT_EQ(f.session().log()->size(), 3u);
  const CutLogEntry& next = f.session().log()->last();
  EXPECT_GT(next.stepIndex, logged.back().stepIndex);
  EXPECT_GT(next.removedMm3, 0);
  EXPECT_NEAR(next.cumulativeMm3, removed + next.removedMm3, 1e-6 * next.cumulativeMm3);
  EXPECT_NEAR(f.session().initialVolumeMm3() - f.session().bone()->current().volume(), next.cumulativeMm3,
              1e-6 * next.cumulativeMm3);
  ASSERT_TRUE(settledCopy(w));                // and the copy is kept up to date again
  EXPECT_EQ(w.recovery()->found()->cuts, 3);  // with the restored rows
  // A bone that replaces this one (a CT import, undoable) starts its cumulative volume from its own; the
  // restored bone, swapped back, from what was removed from it.
  const double restoredStart = f.session().initialVolumeMm3();
  BoneContent other;
  other.history = BoneHistory(BoneState::fromMesh(buildBox(Bounds{{0, 0, 0}, {10, 10, 10}})));
  other.cuttable = true;
  f.session().exchangeBone(other);
  EXPECT_NEAR(f.session().initialVolumeMm3(), 1000.0, 1e-9);
  f.session().exchangeBone(other);
  EXPECT_EQ(f.session().initialVolumeMm3(), restoredStart);
  EXPECT_TRUE(closeAnswering(w, {ModalAnswers::button(QMessageBox::Discard)}, 1));
  EXPECT_FALSE(RecoveryFiles(dir.filePath("recovery")).found());
  EXPECT_TRUE(QDir(dir.filePath("recovery")).entryList({"history-*", "bone.*", "beside*"}, QDir::Files).isEmpty());
}

// Save writes the cut bone only: a bone moved beside with cuts no save wrote goes into the copy even once the cut
// bone is saved, and the next window restores it beside the bone, still unsaved.
TEST(GuiRecovery, ABoneBesideWithUnsavedCutsIsCopiedAndRestoredBesideTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  double besideVolume = 0;
  {
    GuiFixture crashed;
    MainWindow& w = *crashed.window;
    ReamSession& s = crashed.session();
    w.enableRecovery(dir.filePath("recovery"), 0);
    cutOnce(s);  // the scapula's cut
    besideVolume = s.bone()->current().volume();
    // A second bone beside it (the scapula's own shape, 200 mm away), then cut that one instead.
    TriangleMesh other = movedAside(s.bone()->current());
    auto node = std::make_unique<BoneNode>("second");
    BoneContent content;
    content.name = "second";
    content.history = BoneHistory(BoneState::fromMesh(other), "test");
    content.cuttable = true;
    node->swapContent(content);
    std::vector<std::unique_ptr<BoneNode>> nodes;
    nodes.push_back(std::move(node));
    s.undoStack()->push(new OtherBonesCommand(s.document(), std::move(nodes), "Add second beside"));
    ASSERT_TRUE(w.cutBoneBesideInstead());
    ASSERT_TRUE(s.waitIdle(60000));
    ASSERT_TRUE(w.saveBoneAs(dir.filePath("second.ply")));  // the cut bone is saved, the scapula's cut is not
    EXPECT_FALSE(w.hasUnsavedChanges());
    const std::optional<RecoveredBone> copy = settledCopy(w);
    ASSERT_TRUE(copy);
    ASSERT_EQ(copy->beside.size(), 1u);
    EXPECT_TRUE(QFileInfo::exists(copy->beside[0].path));
  }  // gone without a close
  GuiFixture f;
  MainWindow& w = *f.window;
  const BoneNode* beside = restoreWithOneBoneBeside(f, dir);
  ASSERT_NE(beside, nullptr);
  EXPECT_NEAR(beside->current().volume(), besideVolume, 1e-9 * besideVolume);
  EXPECT_TRUE(QString::fromStdString(beside->name()).contains("(recovered)"));
  EXPECT_EQ(w.bonesBesideWithUnsavedCuts().size(), 1);  // kept nowhere but in the copy: closing asks
  EXPECT_EQ(w.otherBones()->shownBones(), 1u);
  // Swapped, the restored cut bone goes beside with no cut in its (new) history: still unsaved, still asked
  // about once the other one is saved.
  ASSERT_TRUE(w.cutBoneBesideInstead());
  ASSERT_TRUE(f.session().waitIdle(60000));
  QTemporaryDir out;
  ASSERT_TRUE(w.saveBoneAs(out.filePath("saved.ply")));
  EXPECT_EQ(w.bonesBesideWithUnsavedCuts().size(), 1);
}

// A bone a CT import replaced is held by the undo history only, which a restore does not bring back: with cuts no
// save wrote it goes into the copy even once the new bone is saved, and comes back beside the restored bone.
TEST(GuiRecovery, ABoneAnImportReplacedWithUnsavedCutsIsCopiedAndRestoredBesideTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  double replacedVolume = 0;
  {
    GuiFixture crashed;
    MainWindow& w = *crashed.window;
    ReamSession& s = crashed.session();
    w.enableRecovery(dir.filePath("recovery"), 0);
    cutOnce(s);  // the scapula's cut
    replacedVolume = s.bone()->current().volume();
    TriangleMesh other = movedAside(s.bone()->current());  // the importer's place
    ImportedBone imported;
    imported.mesh = std::move(other);
    imported.cuttable = true;
    s.undoStack()->push(new ReplaceBoneCommand(s, boneContentFrom(std::move(imported), "ct bone", "import"), "Import ct bone"));
    ASSERT_TRUE(s.waitIdle(60000));
    ASSERT_TRUE(w.saveBoneAs(dir.filePath("ct.ply")));  // the new bone is saved, the replaced scapula's cut is not
    EXPECT_FALSE(w.hasUnsavedChanges());
    ASSERT_EQ(w.replacedBonesWithUnsavedCuts().size(), 1);
    const std::optional<RecoveredBone> copy = settledCopy(w);
    ASSERT_TRUE(copy);
    ASSERT_EQ(copy->beside.size(), 1u);
    EXPECT_TRUE(copy->beside[0].name.contains("replaced by a CT import")) << copy->beside[0].name.toStdString();
  }  // gone without a close
  GuiFixture f;
  MainWindow& w = *f.window;
  const BoneNode* beside = restoreWithOneBoneBeside(f, dir);
  ASSERT_NE(beside, nullptr);
  EXPECT_NEAR(beside->current().volume(), replacedVolume, 1e-9 * replacedVolume);
  EXPECT_TRUE(QString::fromStdString(beside->name()).contains("replaced by a CT import")) << beside->name();
  EXPECT_EQ(w.bonesBesideWithUnsavedCuts().size(), 1);  // kept nowhere but in the copy: closing asks
}

// A log that cannot be read back (damaged after the crash) does not stop the bone's restore; the message
// names the file and the problem, and the log is kept as a file for the user.
TEST(GuiRecovery, ALogThatCannotBeReadBackIsReportedAndKept) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  const double volume = crashAfterOneCut(dir);
  const std::optional<RecoveredBone> copy = RecoveryFiles(dir.filePath("recovery")).found();
  ASSERT_TRUE(copy && !copy->logPath.isEmpty());
  {
    QFile log(copy->logPath);
    ASSERT_TRUE(log.open(QIODevice::Append));
    log.write("3,not a time\n");  // a torn last row
  }
  GuiFixture f;
  MainWindow& w = *f.window;
  restoreExpectingAMessage(w, dir);
  EXPECT_NEAR(f.session().bone()->current().volume(), volume, 1e-9 * volume);  // the bone is back
  EXPECT_TRUE(f.session().log()->empty());
  const std::string message = w.lastError().toStdString();
  EXPECT_NE(message.find(QFileInfo(copy->logPath).fileName().toStdString() + ":3: 2 fields where the header has 28"),
            std::string::npos) << message;
  ASSERT_FALSE(w.recoveredLogPath().isEmpty());
  EXPECT_NE(message.find(w.recoveredLogPath().toStdString()), std::string::npos) << message;
  EXPECT_EQ(lines(w.recoveredLogPath()), 3);  // the header, the cut and the torn row, as they were
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
}

// The undo history's journal damaged after the crash: the restore goes on with the recovered bone as its
// history's only state, and the message names the file, the problem and where the journal is kept.
TEST(GuiRecovery, AnUndoHistoryThatCannotBeReadBackIsReportedAndKept) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  const double volume = crashAfterOneCut(dir);
  const std::optional<RecoveredBone> copy = RecoveryFiles(dir.filePath("recovery")).found();
  ASSERT_TRUE(copy && !copy->historyPath.isEmpty());
  {
    QFile journal(copy->historyPath);
    ASSERT_TRUE(journal.resize(journal.size() - 40));  // the cut's record torn
  }
  GuiFixture f;
  MainWindow& w = *f.window;
  restoreExpectingAMessage(w, dir);
  EXPECT_NEAR(f.session().bone()->current().volume(), volume, 1e-9 * volume);  // the bone is back
  EXPECT_EQ(f.session().bone()->history().size(), 1u);
  EXPECT_EQ(f.session().undoStack()->count(), 0);
  EXPECT_EQ(f.session().log()->size(), 1u);  // and its log
  const std::string message = w.lastError().toStdString();
  EXPECT_NE(message.find(QFileInfo(copy->historyPath).fileName().toStdString()), std::string::npos) << message;
  EXPECT_NE(message.find("is not in the journal"), std::string::npos) << message;
  const QStringList kept = QDir(dir.filePath("recovery/restored")).entryList({"*_history-*.rsj"}, QDir::Files);
  ASSERT_EQ(kept.size(), 1);
  EXPECT_NE(message.find(kept.front().toStdString()), std::string::npos) << message;
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
}

TEST(GuiRecovery, DiscardingTheOfferDeletesTheCopy) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  {
    GuiFixture crashed;
    crashed.window->enableRecovery(dir.filePath("recovery"), 0);
    cutOnce(crashed.session());
    ASSERT_TRUE(settledCopy(*crashed.window));
  }
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Discard")});
  w.enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return answers.seen() == 1 && !QApplication::activeModalWidget(); }, 30000));
  EXPECT_FALSE(w.recovery()->found());
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);  // the default case stays
  EXPECT_FALSE(w.hasUnsavedChanges());
}

// The copy is read back on a worker behind a progress dialog (seconds for a CT bone of millions of faces). Its
// Cancel leaves the window's bone, and keeps the copy for the next start: this window writes no copy of its own
// over it; the next window offers it again and restores it.
TEST(GuiRecovery, ACancelledRestoreKeepsTheCopyForTheNextStart) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  const double crashedVolume = crashAfterOneCut(dir);
  {
    GuiFixture f;
    MainWindow& w = *f.window;
    const std::uint64_t revision = f.session().bone()->currentRevision();
    CancelProgressOnShow cancel;
    ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
    w.enableRecovery(dir.filePath("recovery"), 0);
    ASSERT_TRUE(QTest::qWaitFor([&] { return answers.seen() == 1 && cancel.pressed == 1 && !QApplication::activeModalWidget(); },
                                30000));
    QTest::qWait(50);
    EXPECT_EQ(f.session().bone()->currentRevision(), revision);  // the default case stays
    EXPECT_TRUE(w.statusBar()->currentMessage().contains("Restore cancelled")) << w.statusBar()->currentMessage().toStdString();
    EXPECT_EQ(w.recovery(), nullptr);  // no longer this window's folder
    cutOnce(f.session());  // unsaved work of this window: no copy replaces the one kept
    QTest::qWait(200);
  }
  GuiFixture g;
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  g.window->enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return answers.seen() == 1 && !QApplication::activeModalWidget(); }, 30000));
  ASSERT_TRUE(QTest::qWaitFor([&] { return g.window->windowTitle().contains("(recovered)"); }, 30000));
  EXPECT_NEAR(g.session().bone()->current().volume(), crashedVolume, 1e-9 * crashedVolume);
}

TEST(GuiRecovery, ACorruptCopyIsReportedAndKept) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  const QString folder = dir.filePath("recovery");
  ASSERT_TRUE(QDir().mkpath(folder));
  auto write = [&](const QString& name, const QByteArray& bytes) {
    QFile file(QDir(folder).filePath(name));
    ASSERT_TRUE(file.open(QIODevice::WriteOnly));
    file.write(bytes);
  };
  write("recovery.json", R"({"slot": "a", "name": "scapula", "cuts": 3, "written": "2026-11-28T10:00:00Z"})");
  write("bone.a.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2\n");  // cut short
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  ModalAnswers answers({ModalAnswers::click("RecoveryDialog", "Restore")});
  w.enableRecovery(folder, 0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !w.lastError().isEmpty(); }, 30000));
  EXPECT_EQ(answers.seen(), 1);
  EXPECT_TRUE(w.lastError().contains("bone.a.ply")) << w.lastError().toStdString();  // names the file
  EXPECT_TRUE(w.lastError().contains(folder)) << w.lastError().toStdString();        // and where the copy stays
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);  // the bone open before is still there
  EXPECT_EQ(w.recovery(), nullptr);                            // the window leaves the folder alone
  EXPECT_TRUE(RecoveryFiles(folder).found());                  // the copy is kept for the user
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
}

TEST(GuiRecovery, ASecondWindowLeavesTheFirstOnesCopyAlone) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture first;
  first.window->enableRecovery(dir.filePath("recovery"), 0);
  ASSERT_NE(first.window->recovery(), nullptr);
  GuiFixture second;
  second.window->enableRecovery(dir.filePath("recovery"), 0);
  EXPECT_EQ(second.window->recovery(), nullptr);  // the folder is the first window's
  cutOnce(second.session());
  QTest::qWait(100);
  EXPECT_FALSE(first.window->recovery()->found());
}

}  // namespace
}  // namespace reamsim::ui::test
