// Reaming actions through the real window: "Ream to depth" measures from the first contact (searched after
// the steps queued before it); a move by hand during a queued feed starts where the reamer is shown (it
// interrupts the feed, it does not jump to its end).
#include <QAction>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QLabel>
#include <QInputDialog>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <algorithm>
#include <cmath>
#include <QProgressBar>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest/QTest>

#include "GuiEnvironment.h"
#include "GuiHelpers.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamBackends.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"
#include "reamsim/tools/ReamedSurface.h"

namespace reamsim::ui::test {
namespace {

// The bundled bone as the window opens it: cuttable, no frame, no file facts.
ImportedBone boneAsOpened() {
  ImportedBone bone;
  bone.mesh = loadDefaultBone().mesh;
  bone.cuttable = true;
  return bone;
}

// `start` advanced along its axis to `mm` past where the reamer first touches the bone.
Pose pastFirstContact(ReamSession& s, const Pose& start, double mm) {
  return advancedAlongAxis(start, *advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), start, 100) + mm);
}

// The pose turned by 60 degrees about its tip: in the bone, a chain of 54 placements for the default reamer.
Pose turned60(const Pose& p) {
  Pose q = p;
  const Vec3 across = normalized(cross(p.axis, Vec3{1, 0, 0}));
  q.axis = normalized(normalized(p.axis) * 0.5 + across * std::sqrt(0.75));
  return q;
}

// Places the reamer at the plan's first pose (in front of the glenoid, not touching) and waits for that
// step; returns the pose.
Pose placeAtThePlanStart(ReamSession& s) {
  const Pose start = s.plan()->poses().front();
  s.moveReamer(start);
  EXPECT_TRUE(s.waitIdle(60000));
  return start;
}

// Places the reamer (nothing swept) `mm` past where it first touches the bone in front of the glenoid and
// waits for that step; returns the pose.
Pose placeInTheBone(ReamSession& s, double mm) {
  const Pose start = pastFirstContact(s, s.plan()->poses().front(), mm);
  s.moveReamer(start);
  EXPECT_TRUE(s.waitIdle(60000));
  return start;
}

TEST(GuiReaming, ReamToDepthStartsAtTheFirstContact) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = s.plan()->poses().front();  // in front of the glenoid, not touching
  s.moveReamer(start);
  ASSERT_TRUE(s.waitIdle(60000));
  const double expectedApproach =
      *advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), start, 100);
  ASSERT_GT(expectedApproach, 0.2);
  const double volumeBefore = s.bone()->current().volume();
  w.setSteps(0.5, 2.0, 0.25);

  w.reamToDepth(1.0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !w.contactSearchRunning(); }, 60000));
  ASSERT_TRUE(s.waitIdle(120000));
  EXPECT_NEAR(w.lastApproachMm(), expectedApproach, 1e-9);
  // The reamer ends 1 mm past the first contact, along its axis.
  const Pose end = s.reamer()->pose();
  EXPECT_NEAR(dot(end.tip - start.tip, normalized(start.axis)), expectedApproach + 1.0, 1e-9);
  EXPECT_LT(s.bone()->current().volume(), volumeBefore - 10.0);
  // How deep the surface went, measured on the bone (the depth colouring's numbers): about 1 mm.
  EXPECT_GT(w.view()->maxDepthMm(), 0.8);
  EXPECT_LT(w.view()->maxDepthMm(), 1.05);
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
}

// The log panel's "Measure seat": the reamed surface at the reamer's pose, as modules/tools measures it;
// cleared by the next cut (it was measured on the bone before it).
TEST(GuiReaming, MeasureSeatReportsTheReamedSurfaceAtThePose) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeInTheBone(s, 1.0);
  auto* panel = w.findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  auto* button = panel->findChild<QPushButton*>("MeasureSeat");
  auto* label = panel->findChild<QLabel*>("SeatReport");
  ASSERT_NE(button, nullptr);
  ASSERT_NE(label, nullptr);
  QTest::mouseClick(button, Qt::LeftButton);
  const ReamedSurfaceReport expected =
      measureReamedSurface(s.bone()->current().toMesh(), s.reamer()->spec(), s.reamer()->pose());
  ASSERT_GT(expected.seatedFraction, 0.05);  // 1 mm past the first contact: part of the face sits on bone
  const QString percent = QLocale().toString(100 * expected.seatedFraction, 'f', 1) + " % of the cutting face on bone";
  EXPECT_TRUE(label->text().contains(percent)) << label->text().toStdString() << " / " << percent.toStdString();
  EXPECT_TRUE(label->text().contains(QLocale().toString(expected.facetSagMm, 'f', 4))) << label->text().toStdString();
  // The next cut leaves the measurement behind: the label is cleared.
  s.moveReamer(advancedAlongAxis(start, 0.25));
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(label->text().isEmpty()) << label->text().toStdString();
}

// Stop right after Ream to depth, while its contact search runs: the search's answer starts no feed.
TEST(GuiReaming, StopDuringReamToDepthsSearchStartsNoFeed) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  ASSERT_TRUE(s.waitIdle(60000));
  const std::uint64_t revision = s.bone()->currentRevision();
  w.reamToDepth(1.0);
  w.action("stop")->trigger();  // before the event loop has delivered the search's answer
  ASSERT_TRUE(s.waitIdle(60000));
  QTest::qWait(100);
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.bone()->currentRevision(), revision);
  EXPECT_TRUE(s.log()->empty());
  // Asked again, it reams.
  w.reamToDepth(1.0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !s.log()->empty() && !s.busy(); }, 60000));
}

TEST(GuiReaming, ReamToDepthWithNoBoneAheadSaysSo) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  const Bounds b = f.session().bone()->current().bounds();
  f.session().moveReamer(Pose{{b.center().x, b.center().y, b.max.z + 50}, {0, 0, 1}, 0});  // above, pointing away
  ASSERT_TRUE(f.session().waitIdle(60000));
  const std::size_t cuts = f.session().log()->size();
  w.reamToDepth(1.0);
  ASSERT_TRUE(QTest::qWaitFor([&] { return !w.contactSearchRunning(); }, 60000));
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_TRUE(w.lastError().contains("meets no bone")) << w.lastError().toStdString();
  EXPECT_EQ(f.session().log()->size(), cuts);
}

// "Ream to depth" asked while steps are still queued searches after them, on the bone they leave: here a cut
// 1 mm past the first contact and a move back to 1 mm before it, so the reamer meets its own cavity's
// floor 2 mm ahead (the bone before those steps would say 1 mm).
TEST(GuiReaming, ReamToDepthBehindQueuedStepsSearchesTheBoneTheyLeave) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeAtThePlanStart(s);
  const std::size_t cutsBefore = s.log()->size();
  const Pose inside = pastFirstContact(s, start, 1.0), backedOut = pastFirstContact(s, start, -1.0);
  w.setSteps(0.5, 2.0, 0.25);
  s.runSteps({inside, backedOut});
  w.reamToDepth(0.5);  // from where the queued steps end: backedOut
  ASSERT_TRUE(QTest::qWaitFor([&] { return !w.contactSearchRunning(); }, 60000));
  ASSERT_TRUE(s.waitIdle(120000));
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  // 2 mm to the floor the reamer's own facets cut, less what the band clean-up moved it by: up to half the
  // facets' 17 um sag per operation, more where the steps' clean-ups meet (18 um here; 1 mm would be the
  // bone before the steps).
  EXPECT_NEAR(w.lastApproachMm(), 2.0, 0.03);
  EXPECT_GT(s.log()->size(), cutsBefore + 1);  // the cut at `inside`, then the feed below the floor
  EXPECT_NEAR(dot(s.reamer()->pose().tip - backedOut.tip, normalized(backedOut.axis)), w.lastApproachMm() + 0.5, 1e-9);
}

// A move by hand clears the queue, a contact search waiting in it too: the "ream to depth" is dropped
// without a message and nothing is fed.
TEST(GuiReaming, AHandMoveDropsAQueuedReamToDepth) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeAtThePlanStart(s);
  s.runSteps({pastFirstContact(s, start, 1.0), pastFirstContact(s, start, 1.25)});
  w.reamToDepth(0.5);
  ASSERT_TRUE(w.contactSearchRunning());
  const Pose away = advancedAlongAxis(start, -5.0);
  s.moveReamer(away);
  EXPECT_FALSE(w.contactSearchRunning());
  ASSERT_TRUE(s.waitIdle(120000));
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_EQ(w.lastApproachMm(), -1);  // never answered
  EXPECT_EQ(s.reamer()->pose().tip, away.tip);
}

TEST(GuiReaming, HandMoveDuringAFeedStartsWhereTheReamerIsShown) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeAtThePlanStart(s);
  w.setSteps(0.5, 2.0, 0.2);
  w.feedBy(4.0);  // 20 feed steps queued
  const Pose shown = s.reamer()->pose();
  QTest::keyClick(w.windowHandle(), Qt::Key_Up);  // +0.5 mm in Y, by hand
  const Pose moved = s.reamer()->pose();
  EXPECT_NEAR(moved.tip.y - shown.tip.y, 0.5, 1e-9);
  EXPECT_NEAR(moved.tip.x, shown.tip.x, 1e-9);
  EXPECT_NEAR(moved.tip.z, shown.tip.z, 1e-9);
  ASSERT_TRUE(s.waitIdle(120000));
  // The rest of the feed was interrupted: the reamer did not travel the 4 mm.
  EXPECT_LT(dot(s.reamer()->pose().tip - start.tip, normalized(start.axis)), 1.0);
}

TEST(GuiReaming, HeldFeedKeyQueuesOnlyAFewSteps) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  // Already in the bone, so that every feed step cuts.
  const Pose start = placeInTheBone(s, 0.3);
  w.setSteps(0.5, 2.0, 0.2);
  // Twelve presses of the feed key within one turn of the event loop, as a held key's repeats reach a busy
  // window: no cut can finish between them, however fast cuts are (QTest::keyClick processes events after
  // each press, so with cuts faster than a frame every press found the queue empty).
  QAction* feed = w.action("reamer_feed_forward");
  ASSERT_NE(feed, nullptr);
  EXPECT_TRUE(feed->shortcuts().contains(QKeySequence(Qt::Key_PageDown)));
  std::size_t maxQueued = 0;
  for (int i = 0; i < 12; ++i) {
    feed->trigger();
    maxQueued = std::max(maxQueued, s.queuedSteps());
  }
  EXPECT_LE(maxQueued, 4u);
  ASSERT_TRUE(s.waitIdle(120000));
  const double advanced = dot(s.reamer()->pose().tip - start.tip, normalized(start.axis));
  EXPECT_GE(advanced, 0.2 - 1e-9);
  EXPECT_LT(advanced, 12 * 0.2 - 1e-9);  // some presses were ignored
}

TEST(GuiReaming, UndoStopsAQueuedSequence) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  s.moveReamer(s.plan()->poses().front());
  ASSERT_TRUE(s.waitIdle(60000));
  w.setSteps(0.5, 2.0, 0.2);
  w.reamToDepth(3.0);  // the approach, then 15 feed steps
  ASSERT_TRUE(QTest::qWaitFor([&] { return s.cutsCommitted() >= 2; }, 120000));
  ASSERT_GT(s.queuedSteps(), 0u);
  w.action("undo")->trigger();
  EXPECT_EQ(s.queuedSteps(), 0u);
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_LT(s.cutsCommitted(), 16u);
  EXPECT_TRUE(s.undoStack()->canRedo());  // nothing was cut after the undo
}

TEST(GuiReaming, KeyMovesSweepPlacementsDoNot) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  placeInTheBone(s, 0.5);  // placed: nothing swept
  EXPECT_FALSE(s.lastStepSwept());
  w.setSteps(3.0, 2.0, 0.2);
  QTest::keyClick(w.windowHandle(), Qt::Key_Up);  // 3 mm sideways, in the bone: the sweep is cut
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(s.lastStepSwept());
  QTest::keyClick(w.windowHandle(), Qt::Key_A);  // a 2 degree turn: cut in sub-steps along it
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(s.lastStepSwept());
  w.setSteps(3.0, 0.5, 0.2);
  QTest::keyClick(w.windowHandle(), Qt::Key_A);  // 0.5 degrees: the end pose covers it (ridges under 1 µm)
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(s.lastStepSwept());
}

TEST(GuiReaming, AKeyMoveLogsWhereItFirstMetTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  placeInTheBone(s, 0.5);
  w.setSteps(3.0, 2.0, 0.2);
  QTest::keyClick(w.windowHandle(), Qt::Key_Up);  // 3 mm sideways from inside the bone: met at its start
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_TRUE(s.lastStepSwept());
  const CutLogEntry& e = s.log()->entries().back();
  ASSERT_TRUE(e.moveContactT.has_value());
  EXPECT_EQ(*e.moveContactT, 0.0);
  auto* table = w.findChild<QTableWidget*>("LogTable");
  ASSERT_NE(table, nullptr);
  ASSERT_GT(table->rowCount(), 0);
  const QString tip = table->item(table->rowCount() - 1, 5)->toolTip();
  EXPECT_TRUE(tip.startsWith("the move first met the bone " + QLocale().toString(0.0, 'f', 1) + " % of the way"))
      << tip.toStdString();
  // The reamer that made the step, with its size.
  EXPECT_EQ(e.reamer, s.reamer()->spec().name);
  EXPECT_EQ(table->item(table->rowCount() - 1, 7)->text().toStdString(), s.reamer()->spec().name);
  EXPECT_TRUE(table->item(table->rowCount() - 1, 7)->toolTip().startsWith("Ø ")) << table->item(table->rowCount() - 1, 7)->toolTip().toStdString();
}

TEST(GuiReaming, StopEndsALongSwingAndLeavesTheBoneAsItWas) {
  // A 60 degree turn in the bone is a chain of 54 placements (one Boolean each); Stop (Esc) while it
  // runs ends it at the next Boolean: nothing is committed, no error is shown, the reamer goes back to
  // where the step started, and the next step cuts as usual.
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeInTheBone(s, 0.5);
  const std::uint64_t revision = s.bone()->currentRevision();
  const std::size_t logged = s.log()->size();
  const double volume = s.bone()->current().volume();
  const Pose swung = turned60(start);

  QSignalSpy stopped(&s, &ReamSession::stepCancelled);
  s.runSteps({swung});  // queued steps start at once: the swing is running now
  ASSERT_TRUE(s.busy());
  w.action("stop")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(stopped.count(), 1);
  EXPECT_EQ(s.bone()->currentRevision(), revision);
  EXPECT_EQ(s.log()->size(), logged);
  EXPECT_EQ(s.bone()->current().volume(), volume);
  EXPECT_EQ(s.reamer()->pose().tip, start.tip);
  EXPECT_EQ(s.reamer()->pose().axis, start.axis);
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();

  s.runSteps({advancedAlongAxis(start, 0.3)});  // the engine resyncs and cuts
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(stopped.count(), 1);
  EXPECT_LT(s.bone()->current().volume(), volume - 1.0);
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();

  // A new bone while a swing runs stops it too, and the new bone keeps its own start pose: the stopped
  // step belonged to the old bone (loadBone waits for it; its result arrives after the new bone is in).
  s.runSteps({swung});
  ASSERT_TRUE(s.busy());
  ImportedBone other;
  other.mesh = s.bone()->current().toMesh();
  other.cuttable = true;
  const Pose newStart{start.tip + Vec3{0, 0, 40}, start.axis, 0};
  s.loadBone(std::move(other), "the same bone again", newStart);
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.reamer()->pose().tip, newStart.tip);
  EXPECT_EQ(stopped.count(), 1);  // not a Stop: nothing to report
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
}

TEST(GuiReaming, ALongSwingReportsHowFarItHasGot) {
  // The 60 degree swing's 54 Booleans take a few hundred milliseconds here: the session reports them
  // every 100 ms (the window shows them on the progress bar), counting up to the whole chain.
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  const Pose start = placeInTheBone(s, 0.5);
  s.runSteps({advancedAlongAxis(start, 0.1), advancedAlongAxis(start, 0.2)});  // a sequence, finished first
  ASSERT_TRUE(s.waitIdle(60000));
  const Pose swung = turned60(advancedAlongAxis(start, 0.2));
  QSignalSpy progress(&s, &ReamSession::stepProgress);
  auto* bar = f.window->findChild<QProgressBar*>("StepProgress");
  ASSERT_NE(bar, nullptr);
  bool barShown = false;  // read after the window's own handler (connected first)
  QObject::connect(&s, &ReamSession::stepProgress, [&] { barShown = barShown || bar->isVisible(); });
  s.moveReamer(swung, true);  // by hand: no sequence, so the bar shows the step's Booleans
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_GE(progress.count(), 1);
  EXPECT_TRUE(barShown);
  int last = 0;
  for (const QList<QVariant>& p : progress) {
    EXPECT_EQ(p.at(1).toInt(), 54);
    EXPECT_GE(p.at(0).toInt(), last);  // it only counts up
    EXPECT_LE(p.at(0).toInt(), 54);
    last = p.at(0).toInt();
  }
  EXPECT_TRUE(s.lastStepSwept());
  EXPECT_TRUE(f.window->lastError().isEmpty()) << f.window->lastError().toStdString();
}

TEST(GuiReaming, ASequenceOfOneSwingCountsItsBooleans) {
  // A sequence of one step has nothing to count but that step: the bar shows the swing's Booleans (it
  // showed "0 of 1" until the step ended).
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  const Pose start = placeInTheBone(s, 0.5);
  auto* bar = f.window->findChild<QProgressBar*>("StepProgress");
  ASSERT_NE(bar, nullptr);
  int largestMaximum = -1;  // read after the window's own handlers (connected first)
  QObject::connect(&s, &ReamSession::stepProgress, [&] {
    if (bar->isVisible()) largestMaximum = std::max(largestMaximum, bar->maximum());
  });
  s.runSteps({advancedAlongAxis(start, 0.2)});  // a feed: one Boolean, nothing to report
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(largestMaximum, -1);
  s.runSteps({turned60(advancedAlongAxis(start, 0.2))});  // the swing of the test above, as a sequence
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(largestMaximum, 54);
  EXPECT_FALSE(bar->isVisible());
  EXPECT_TRUE(s.lastStepSwept());
  EXPECT_TRUE(f.window->lastError().isEmpty()) << f.window->lastError().toStdString();
}

}  // namespace
}  // namespace reamsim::ui::test

namespace reamsim::ui::test {
namespace {

// Sets the locale numbers are shown in for one test (QLocale's default), and puts the old one back.
class ShownLocale {
 public:
  explicit ShownLocale(const QLocale& l) { QLocale::setDefault(l); }
  ~ShownLocale() { QLocale::setDefault(before_); }

 private:
  QLocale before_;
};

// The numbers a user reads (log table, contact point, the undo entry) are in the user's locale — 1,234 mm³ in
// Germany — while the files keep the decimal point (docs/GUI.md "Numbers in files").
TEST(GuiReaming, ShownNumbersFollowTheUsersLocaleFilesDoNot) {
  REAMSIM_REQUIRE_DISPLAY();
  const QLocale german(QLocale::German, QLocale::Germany);
  ShownLocale shown(german);
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  placeInTheBone(s, 1.0);
  ASSERT_FALSE(s.log()->entries().empty());
  const CutLogEntry& e = s.log()->entries().back();
  auto* table = w.findChild<QTableWidget*>("LogTable");
  ASSERT_NE(table, nullptr);
  const int row = table->rowCount() - 1;
  ASSERT_GE(row, 0);
  const QString removed = table->item(row, 1)->text();
  EXPECT_TRUE(removed.contains(',') && !removed.contains('.')) << removed.toStdString();
  bool ok = false;
  EXPECT_NEAR(german.toDouble(removed, &ok), e.removedMm3, 5e-4);
  EXPECT_TRUE(ok) << removed.toStdString();
  ASSERT_TRUE(e.contactPoint.has_value());
  const QStringList xyz = table->item(row, 5)->text().split("; ");
  ASSERT_EQ(xyz.size(), 3) << table->item(row, 5)->text().toStdString();
  EXPECT_NEAR(german.toDouble(xyz[0]), e.contactPoint->x, 5e-3);
  EXPECT_NEAR(german.toDouble(xyz[2]), e.contactPoint->z, 5e-3);
  const QUndoStack* undo = s.undoStack();
  ASSERT_GT(undo->count(), 0);
  EXPECT_TRUE(undo->text(undo->count() - 1).contains(german.toString(e.removedMm3, 'f', 2)))
      << undo->text(undo->count() - 1).toStdString();
  // The CSV the panel exports is the same as in any locale.
  auto* panel = w.findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  QTemporaryDir out;
  QString error;
  ASSERT_TRUE(QMetaObject::invokeMethod(panel, "exportCsv", Q_RETURN_ARG(QString, error),
                                        Q_ARG(QString, out.filePath("log.csv")), Q_ARG(bool, false)));
  ASSERT_TRUE(error.isEmpty()) << error.toStdString();
  const std::vector<CutLogEntry> back = readCutLogCsv(out.filePath("log.csv").toStdString());
  ASSERT_EQ(back.size(), s.log()->entries().size());
  EXPECT_NEAR(back.back().removedMm3, e.removedMm3, 1e-9 * e.removedMm3);
}

// Reamer → Choose the reamer…: picked from the presets in the list the window shows; the reamer keeps its pose,
// and the next cut is made and logged with it.
TEST(GuiReaming, ChoosingAReamerCutsAndLogsWithIt) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  ASSERT_EQ(s.reamer()->spec().name, "glenoid-36-R30");
  const Pose before = placeAtThePlanStart(s);
  QStringList offered;
  ModalAnswers answers({[&offered](QWidget* modal) {
    auto* dialog = qobject_cast<QInputDialog*>(modal);
    ASSERT_NE(dialog, nullptr) << "expected the reamer list, got " << modal->metaObject()->className();
    offered = dialog->comboBoxItems();
    for (const QString& item : offered)
      if (item.startsWith("glenoid-44-R35 ")) dialog->setTextValue(item);
    dialog->accept();
  }});
  w.action("choose_reamer")->trigger();
  EXPECT_EQ(answers.seen(), 1);
  EXPECT_EQ(offered.size(), 13) << offered.join(", ").toStdString();  // every preset of reamers.json
  EXPECT_TRUE(offered.contains("baseplate-27-flat (Ø 27 mm, flat)")) << offered.join(", ").toStdString();
  ASSERT_EQ(s.reamer()->spec().name, "glenoid-44-R35");
  EXPECT_EQ(s.reamer()->spec().diameterMm, 44.0);
  EXPECT_TRUE(samePose(s.reamer()->pose(), before));
  EXPECT_EQ(s.plan()->reamerSpecName(), "glenoid-44-R35");
  cutOnce(s);
  EXPECT_EQ(s.log()->last().reamer, "glenoid-44-R35");
  EXPECT_EQ(s.log()->last().reamerDiameterMm, 44.0);
  EXPECT_FALSE(w.chooseReamer("glenoid-44-R35"));  // already the reamer: nothing changes
  EXPECT_FALSE(w.chooseReamer("no-such-reamer"));
  EXPECT_TRUE(w.lastError().contains("There is no reamer no-such-reamer in")) << w.lastError().toStdString();
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-44-R35");
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
}

// A reamer chosen while a long swing runs neither stops the swing nor waits for it: the swing is cut and logged
// with the reamer it started with, and the reamer changes once it has finished.
TEST(GuiReaming, AReamerChosenDuringASwingTakesOverAfterIt) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  const Pose start = placeInTheBone(s, 0.5);
  const std::size_t logged = s.log()->size();
  s.runSteps({turned60(start)});  // 54 Booleans: running now
  ASSERT_TRUE(s.busy());
  ASSERT_TRUE(w.chooseReamer("glenoid-44-R35"));
  EXPECT_TRUE(s.busy());                                // the swing goes on
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-36-R30");  // until it has finished
  ASSERT_TRUE(s.waitIdle(120000));
  ASSERT_EQ(s.log()->size(), logged + 1);
  EXPECT_EQ(s.log()->last().reamer, "glenoid-36-R30");
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-44-R35");
  s.runSteps({advancedAlongAxis(turned60(start), 0.5)});
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_EQ(s.log()->size(), logged + 2);
  EXPECT_EQ(s.log()->last().reamer, "glenoid-44-R35");
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
}

// Reamer → Choose a reamer mesh…: a closed solid read from a file, as `reamsim-cli ream --reamer FILE`; it cuts and
// is logged under its file's name. A file that is not a closed solid is refused, naming it, and the reamer stays.
TEST(GuiReaming, AReamerMeshFromAFileCutsAndABadOneIsRefused) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  const TriangleMesh solid = buildCuttingSolid(loadPreset("glenoid-40-R32", reamerPresetsPath()));
  const QString good = dir.filePath("cutter40.stl");
  writeMesh(solid, good.toStdString());
  TriangleMesh open = solid;
  open.triangles.pop_back();
  const QString bad = dir.filePath("open_cutter.stl");
  writeMesh(open, bad.toStdString());

  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  placeAtThePlanStart(s);
  EXPECT_FALSE(w.chooseReamerMesh(bad));
  EXPECT_TRUE(w.lastError().contains("open_cutter.stl")) << w.lastError().toStdString();
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-36-R30");  // unchanged
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();

  ASSERT_TRUE(w.chooseReamerMesh(good));
  EXPECT_EQ(s.reamer()->spec().meshFile, good.toStdString());
  EXPECT_EQ(s.reamer()->cuttingVolume()->triangles.size(), solid.triangles.size());
  EXPECT_TRUE(s.canCut()) << s.cuttingStatus().toStdString();
  cutOnce(s);
  EXPECT_EQ(s.log()->last().reamer, "cutter40.stl");
  EXPECT_GT(s.log()->last().removedMm3, 0.0);
  // A plan naming the mesh beside it runs with it.
  ReamPlan plan;
  plan.reamer = "cutter40.stl";
  plan.poses = {s.plan()->poses().front()};
  const QString planPath = dir.filePath("with_mesh.json");
  writeTextFile(planPath.toStdString(), planToJson(plan));
  ASSERT_TRUE(w.chooseReamer("glenoid-36-R30"));
  ASSERT_TRUE(w.runPlanFile(planPath));
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.reamer()->spec().meshFile, dir.filePath("cutter40.stl").toStdString());
}

// Reamer → Run a plan…: the plan file cuts the bone as `reamsim-cli ream --plan` does: the first pose placed (nothing
// swept to it from where the reamer was), the rest a path whose sideways moves sweep, with the plan's reamer.
// Compared with the command line's controller on the same bone: the reamer first seated in the glenoid by one cut,
// then the plan from a fresh controller (whose first pose is placed, as the command line's).
TEST(GuiReaming, RunningAPlanFileCutsAsTheCommandLineDoes) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);  // the reamer seated 0.5 mm in the glenoid
  const Pose seated = s.reamer()->pose();
  // Three poses with the 40 mm reamer: 3 mm across the axis (placed), 1 mm further (a swept travel), fed 0.3 mm.
  const Vec3 across = normalized(cross(seated.axis, std::abs(seated.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  ReamPlan plan;
  plan.reamer = "glenoid-40-R32";
  Pose p1 = seated;
  p1.tip = seated.tip + 3.0 * across;
  Pose p2 = p1;
  p2.tip = p1.tip + 1.0 * across;
  plan.poses = {p1, p2, advancedAlongAxis(p2, 0.3)};
  const QString planPath = dir.filePath("plan.json");
  writeTextFile(planPath.toStdString(), planToJson(plan));

  // The command line's way, in this process.
  Document doc;
  auto& bone = doc.create<BoneNode>("Bone", BoneState::fromMesh(loadDefaultBone().mesh));
  const ReamerSpec defaultSpec = loadPreset("glenoid-36-R30", reamerPresetsPath());
  auto& reamer = doc.create<ReamerNode>("Reamer", defaultSpec);
  reamer.setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(defaultSpec)));
  auto& log = doc.create<LogNode>("Log");
  ReamController(doc, bone, reamer, log, nullptr, localCutBackendFactory(), makeBvhContactBackend()).moveTo(seated);
  ASSERT_EQ(bone.current().liveTriangleCount(), s.bone()->current().liveTriangleCount());
  const double seatedVolume = bone.current().volume();
  const ReamerSpec planSpec = loadPreset(plan.reamer, reamerPresetsPath());
  reamer.setSpec(planSpec);
  reamer.setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(planSpec)));
  ReamController planRun(doc, bone, reamer, log, nullptr, localCutBackendFactory(), makeBvhContactBackend());
  for (const Pose& p : plan.poses) planRun.moveTo(p);

  ASSERT_TRUE(w.runPlanFile(planPath));
  ASSERT_TRUE(s.waitIdle(120000));
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-40-R32");
  EXPECT_EQ(s.plan()->poses().size(), 3u);
  EXPECT_EQ(s.bone()->current().liveTriangleCount(), bone.current().liveTriangleCount());
  EXPECT_NEAR(s.bone()->current().volume(), bone.current().volume(), 1e-9 * bone.current().volume());
  EXPECT_LT(bone.current().volume(), seatedVolume - 20.0);  // the plan cut
  EXPECT_TRUE(samePose(s.reamer()->pose(), plan.poses.back()));
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();

  // A plan that cannot run says why, naming the file, and leaves the bone as it was.
  const double volume = s.bone()->current().volume();
  const QString broken = dir.filePath("broken.json");
  writeTextFile(broken.toStdString(), "{\"poses\": [{\"tip\": [1, 2], \"axis\": [0, 0, 1]}]}");
  EXPECT_FALSE(w.runPlanFile(broken));
  EXPECT_TRUE(w.lastError().contains("broken.json: poses[0].tip must be an array of 3 numbers")) << w.lastError().toStdString();
  const QString meshReamer = dir.filePath("mesh_reamer.json");
  writeTextFile(meshReamer.toStdString(), "{\"reamer\": \"no_such_cutter.stl\", \"poses\": [{\"tip\": [1, 2, 3], \"axis\": [0, 0, 1]}]}");
  EXPECT_FALSE(w.runPlanFile(meshReamer));  // no such file, and no such preset
  EXPECT_TRUE(w.lastError().contains("neither a mesh file nor a preset")) << w.lastError().toStdString();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.bone()->current().volume(), volume);
  EXPECT_EQ(s.reamer()->spec().name, "glenoid-40-R32");
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
}

// File → Export the reamer's path as a plan: every step on the bone since it was opened — placements, swept
// moves, a feed — replays through the command line's controller to the same bone, to the last face.
TEST(GuiReaming, TheReamersPathExportsAsAPlanThatReplaysTheSession) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;  // its first step: the reamer placed at the plan's start
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);  // a placement 0.5 mm into the glenoid
  const Pose seated = s.reamer()->pose();
  const Vec3 across = normalized(cross(seated.axis, std::abs(seated.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  Pose aside = seated;
  aside.tip = seated.tip + 0.6 * across;
  s.moveReamer(aside, true);  // a move by hand: swept
  ASSERT_TRUE(s.waitIdle(60000));
  Pose elsewhere = seated;
  elsewhere.tip = seated.tip - 1.5 * across;
  s.moveReamer(elsewhere, false);  // placed: nothing swept from `aside`
  ASSERT_TRUE(s.waitIdle(60000));
  s.runSteps({advancedAlongAxis(elsewhere, 0.2), advancedAlongAxis(elsewhere, 0.4)});  // a feed
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_EQ(s.path().size(), 6u);
  EXPECT_FALSE(s.pathInterrupted());

  const QString file = dir.filePath("path.json");
  const QString error = w.exportPath(file);
  ASSERT_TRUE(error.isEmpty()) << error.toStdString();
  const ReamPlan plan = loadPlan(file.toStdString());
  ASSERT_EQ(plan.poses.size(), 6u);
  EXPECT_EQ(plan.reamer, s.reamer()->spec().name);
  EXPECT_EQ(plan.placedPoses, (std::vector<std::size_t>{0, 1, 3}));  // the start, the seat, `elsewhere`

  Document doc;
  auto& bone = doc.create<BoneNode>("Bone", BoneState::fromMesh(loadDefaultBone().mesh));
  const ReamerSpec spec = loadPreset(plan.reamer, reamerPresetsPath());
  auto& reamer = doc.create<ReamerNode>("Reamer", spec);
  reamer.setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(spec)));
  auto& log = doc.create<LogNode>("Log");
  ReamController replay(doc, bone, reamer, log, nullptr, localCutBackendFactory(), makeBvhContactBackend());
  const std::vector<bool> placed = plan.expandedPlacements();
  std::vector<bool> swept;
  for (std::size_t i = 0; i < plan.poses.size(); ++i) swept.push_back(replay.moveTo(plan.poses[i], placed[i]).swept);
  EXPECT_FALSE(swept[3]);  // placed: nothing swept from `aside`
  EXPECT_TRUE(swept[2]);   // the move by hand
  EXPECT_EQ(bone.current().liveTriangleCount(), s.bone()->current().liveTriangleCount());
  EXPECT_NEAR(bone.current().volume(), s.bone()->current().volume(), 1e-9 * bone.current().volume());
  // Replayed with every step a move, the step to `elsewhere` sweeps from `aside`: the flags matter.
  {
    Document doc2;
    auto& bone2 = doc2.create<BoneNode>("Bone", BoneState::fromMesh(loadDefaultBone().mesh));
    auto& reamer2 = doc2.create<ReamerNode>("Reamer", spec);
    reamer2.setCuttingVolume(reamer.cuttingVolume());
    auto& log2 = doc2.create<LogNode>("Log");
    ReamController moves(doc2, bone2, reamer2, log2, nullptr, localCutBackendFactory(), makeBvhContactBackend());
    std::vector<bool> movesSwept;
    for (const Pose& p : plan.poses) movesSwept.push_back(moves.moveTo(p).swept);
    EXPECT_TRUE(movesSwept[3]);
    EXPECT_LE(bone2.current().volume(), bone.current().volume() + 1e-9 * bone.current().volume());
  }

  // After an undo the path no longer leads to the bone shown: the file says so.
  w.action("undo")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(s.pathInterrupted());
  ASSERT_TRUE(w.exportPath(file).isEmpty());
  EXPECT_NE(loadPlan(file.toStdString()).description.find("undone"), std::string::npos);
  // Another reamer part way: one plan cannot hold the path.
  ASSERT_TRUE(w.chooseReamer("glenoid-40-R32"));
  s.moveReamer(advancedAlongAxis(s.reamer()->pose(), -0.2), true);
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_TRUE(w.exportPath(file).contains("reamer changed at step 7")) << w.exportPath(file).toStdString();
  // A new bone starts a new path.
  ImportedBone again;
  again.mesh = loadDefaultBone().mesh;
  again.cuttable = true;
  s.loadBone(std::move(again), "again", seated);
  EXPECT_TRUE(s.path().empty());
  EXPECT_FALSE(s.pathInterrupted());
  EXPECT_TRUE(w.exportPath(file).contains("no step")) << w.exportPath(file).toStdString();
}

// Preview: how much bone a ream to depth would take, computed on a copy while the bone stays as it is; *Ream it*
// then removes that much; Stop stops a preview.
TEST(GuiReaming, APreviewSaysWhatReamToDepthWillRemoveAndCutsNothing) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  ASSERT_TRUE(s.waitIdle(60000));
  const std::uint64_t revision = s.bone()->currentRevision();
  const double volume = s.bone()->current().volume();
  const int commands = s.undoStack()->count();
  QSignalSpy answers(&s, &ReamSession::removalPreviewed);
  w.previewReamToDepth(1.5);
  ASSERT_TRUE(QTest::qWaitFor([&] { return answers.count() == 1; }, 60000));
  const auto answer = answers.at(0).at(0).value<RemovalPreviewAnswer>();
  ASSERT_EQ(int(answer.outcome), int(RemovalPreviewAnswer::Outcome::Computed)) << answer.error.toStdString();
  ASSERT_TRUE(answer.preview.approachMm);
  const double predicted = answer.preview.removedMm3;
  EXPECT_GT(predicted, 100.0);
  EXPECT_EQ(s.bone()->currentRevision(), revision);  // nothing cut, logged or put on the undo stack
  EXPECT_TRUE(s.log()->empty());
  EXPECT_EQ(s.undoStack()->count(), commands);
  EXPECT_TRUE(w.lastPreviewText().contains(QLocale().toString(predicted, 'f', 1) + " mm³")) << w.lastPreviewText().toStdString();
  QMessageBox* box = nullptr;
  ASSERT_TRUE(QTest::qWaitFor([&] { return (box = w.findChild<QMessageBox*>("RemovalPreviewDialog")) != nullptr; }, 5000));
  auto* ream = box->findChild<QPushButton*>("ReamIt");
  ASSERT_NE(ream, nullptr);
  ream->click();
  ASSERT_TRUE(QTest::qWaitFor([&] { return !s.log()->empty() && !s.busy(); }, 60000));
  ASSERT_TRUE(s.waitIdle(60000));
  const double removed = volume - s.bone()->current().volume();
  EXPECT_NEAR(removed, predicted, 1e-6 * predicted);  // what the preview said, cut for real
  // And the seat it said is what Measure seat finds at the reamer's pose after the ream.
  ASSERT_TRUE(answer.preview.seat);
  const ReamedSurfaceReport seat = measureReamedSurface(s.bone()->current().toMesh(), s.reamer()->spec(), s.reamer()->pose());
  EXPECT_NEAR(seat.seatedFraction, answer.preview.seat->seatedFraction, 1e-6);
  EXPECT_TRUE(w.lastPreviewText().contains("sit on bone over " + QLocale().toString(100 * answer.preview.seat->seatedFraction, 'f', 1) + " %"))
      << w.lastPreviewText().toStdString();

  // Stop stops a preview: answered Cancelled, the bone untouched.
  const std::uint64_t cut = s.bone()->currentRevision();
  w.previewReamToDepth(3.0);
  w.action("stop")->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return answers.count() == 2; }, 60000));
  EXPECT_EQ(answers.at(1).at(0).value<RemovalPreviewAnswer>().outcome, RemovalPreviewAnswer::Outcome::Cancelled);
  EXPECT_EQ(s.bone()->currentRevision(), cut);

  // The reamer moved after the preview: *Ream it* cuts nothing and says why.
  w.previewReamToDepth(0.5);
  ASSERT_TRUE(QTest::qWaitFor([&] { return answers.count() == 3; }, 60000));
  QPushButton* stale = nullptr;
  ASSERT_TRUE(QTest::qWaitFor([&] {
    for (QPushButton* b : w.findChildren<QPushButton*>("ReamIt")) stale = b;
    return stale && stale->isVisible();
  }, 5000));
  s.moveReamer(advancedAlongAxis(s.reamer()->pose(), -2.0), false);
  ASSERT_TRUE(s.waitIdle(60000));
  const std::size_t rows = s.log()->size();
  const std::uint64_t moved = s.bone()->currentRevision();
  stale->click();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.log()->size(), rows);
  EXPECT_EQ(s.bone()->currentRevision(), moved);
  EXPECT_TRUE(w.lastError().contains("changed since the preview")) << w.lastError().toStdString();
}

// An educator's session: notes written on cuts go into the exported path with the time of every step; replayed at
// its recorded pace on the bone as opened, each step waits for its time, the notes come back on the replay's
// log rows and are announced, and the replay cuts as the session did. Stop drops the steps still waiting.
TEST(GuiReaming, ANotedPathReplaysAtItsRecordedPaceWithItsNotes) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  cutOnce(s);  // the fixture's placement, then a cut 0.5 mm in
  QTest::qWait(700);  // the trainee pauses
  const Pose seated = s.reamer()->pose();
  s.runSteps({advancedAlongAxis(seated, 0.2), advancedAlongAxis(seated, 0.4)});
  ASSERT_TRUE(s.waitIdle(60000));
  ASSERT_EQ(s.log()->size(), 3u);
  const QString first = QString::fromUtf8("seated: 0.5 mm, \"listen\" for the rim"), last = "final depth";
  ASSERT_TRUE(annotateRow(w, 0, first));
  ASSERT_TRUE(annotateRow(w, 2, last));

  const QString file = dir.filePath("session.json");
  ASSERT_TRUE(w.exportPath(file).isEmpty());
  const ReamPlan plan = loadPlan(file.toStdString());
  ASSERT_EQ(plan.poses.size(), 4u);  // the placement, the cut, two feed steps
  ASSERT_EQ(plan.poseTimesMs.size(), 4u);
  EXPECT_EQ(plan.poseTimesMs[0], 0.0);
  const double span = *plan.poseTimesMs[3];
  EXPECT_GE(*plan.poseTimesMs[2] - *plan.poseTimesMs[1], 600.0);  // the pause is in the file
  ASSERT_EQ(plan.poseNotes.size(), 4u);
  EXPECT_EQ(plan.poseNotes[0], "");  // the placement made no cut, so no row to write on
  EXPECT_EQ(plan.poseNotes[1], first.toStdString());
  EXPECT_EQ(plan.poseNotes[2], "");
  EXPECT_EQ(plan.poseNotes[3], last.toStdString());
  const double volumeAfterSession = s.bone()->current().volume();

  // The bone as opened again, and the session replayed at its pace.
  ImportedBone again;
  again.mesh = loadDefaultBone().mesh;
  again.cuttable = true;
  s.loadBone(std::move(again), "again", seated);
  QSignalSpy notes(&s, &ReamSession::noteReached);
  QElapsedTimer clock;
  clock.start();
  ASSERT_TRUE(w.runPlanFile(file, PlanPace::AsRecorded)) << w.lastError().toStdString();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_GE(double(clock.elapsed()), span - 1.0);  // no step ran before its time
  ASSERT_EQ(s.log()->size(), 3u);
  EXPECT_EQ(s.log()->entries()[0].note, first.toStdString());
  EXPECT_EQ(s.log()->entries()[1].note, "");
  EXPECT_EQ(s.log()->entries()[2].note, last.toStdString());
  ASSERT_EQ(notes.count(), 2);
  EXPECT_EQ(notes.at(1).at(0).toString(), last);
  EXPECT_NEAR(s.bone()->current().volume(), volumeAfterSession, 1e-9 * volumeAfterSession);

  // Stop while a step waits for its time: the rest is dropped, at once.
  ReamPlan slow = plan;
  slow.poseTimesMs[3] = 60000.0;  // a minute in
  const QString slowFile = dir.filePath("slow.json");
  writeTextFile(slowFile.toStdString(), planToJson(slow));
  s.loadBone(boneAsOpened(), "again", seated);
  ASSERT_TRUE(w.runPlanFile(slowFile, PlanPace::AsRecorded));
  for (int i = 0; i < 600 && s.log()->size() < 2; ++i) QTest::qWait(50);
  ASSERT_EQ(s.log()->size(), 2u);
  EXPECT_TRUE(s.busy());  // the last step waits
  clock.restart();
  w.action("stop")->trigger();
  ASSERT_TRUE(s.waitIdle(5000));
  EXPECT_LT(clock.elapsed(), 5000);
  EXPECT_EQ(s.log()->size(), 2u);

  // At 64× the recorded pace the minute takes under a second, and not less.
  s.loadBone(boneAsOpened(), "again", seated);
  w.setReplaySpeed(64);
  clock.restart();
  ASSERT_TRUE(w.runPlanFile(slowFile, PlanPace::AsRecorded));
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_GE(double(clock.elapsed()), 60000.0 / 64 - 1.0);
  EXPECT_EQ(s.log()->size(), 3u);
  w.setReplaySpeed(1e-9);  // out of range: refused, the speed stays
  EXPECT_EQ(w.replaySpeed(), 64.0);
  w.action("replay_speed_100")->trigger();  // the menu's 1×
  EXPECT_EQ(w.replaySpeed(), 1.0);

  // As fast as computed, the same file takes no pause; a plan without times has no pace to replay at.
  s.loadBone(boneAsOpened(), "again", seated);
  ASSERT_TRUE(w.runPlanFile(slowFile));
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.log()->size(), 3u);
  ReamPlan untimed = plan;
  untimed.poseTimesMs.clear();
  writeTextFile(file.toStdString(), planToJson(untimed));
  EXPECT_FALSE(w.runPlanFile(file, PlanPace::AsRecorded));
  EXPECT_TRUE(w.lastError().contains("no pose has a recorded time")) << w.lastError().toStdString();
}

// A placement asked for while a step runs (the Planning dock's Aim, then at once a feed) waits as the pending
// move and stays a placement when the feed queues it: it must not sweep from where the reamer was.
TEST(GuiReaming, APlacementWaitingBehindAStepStaysAPlacement) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  const Pose start = s.plan()->poses().front();
  const Pose near = advancedAlongAxis(start, -1.0);
  Pose far = near;
  far.tip = near.tip + Vec3{0, 15, 0};
  s.runSteps({near});  // running now
  ASSERT_TRUE(s.busy());
  s.moveReamer(far, false);  // placed: waits behind the running step
  s.runSteps({advancedAlongAxis(far, 0.1)});  // queues the waiting placement first
  ASSERT_TRUE(s.waitIdle(60000));
  const auto& path = s.path();
  ASSERT_GE(path.size(), 3u);
  EXPECT_TRUE(samePose(path[path.size() - 2].pose, far));
  EXPECT_TRUE(path[path.size() - 2].placed);
  EXPECT_FALSE(path.back().placed);
}

}  // namespace
}  // namespace reamsim::ui::test
