// The planning dock through the real window: the reamer's version and inclination read in the scapular
// frame of the bundled landmarks, the reamer aimed at asked-for angles, a landmark placed by a click on the
// bone, landmark files.
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QFileInfo>
#include <QMouseEvent>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLocale>
#include <QPushButton>
#include <QStatusBar>
#include <QTableWidget>
#include <QFile>
#include <QImage>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest/QTest>
#include <vtkCamera.h>
#include <vtkRenderer.h>

#include <fstream>

#include "BoneView.h"
#include "GuiEnvironment.h"
#include "GuiHelpers.h"
#include "LandmarksLayer.h"
#include "MainWindow.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/tools/ReamedSurface.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim::ui::test {
namespace {

QDockWidget* planningDock(MainWindow& w) {
  auto* dock = w.findChild<QDockWidget*>("PlanningPanel");
  EXPECT_NE(dock, nullptr) << "the planning plugin's dock is missing";
  return dock;
}

template <class T>
T* part(QDockWidget* dock, const char* name) {
  T* widget = dock->findChild<T*>(name);
  EXPECT_NE(widget, nullptr) << name;
  return widget;
}

AxisAngles reamerAngles(ReamSession& s) {
  return axisAngles(scapularFrame(s.bone()->landmarks()), s.reamer()->pose().axis * -1.0);
}

// Where a world point is drawn in the view, in the widget's own (Qt) coordinates.
QPoint widgetPointOf(BoneView& view, const Vec3& p) {
  vtkRenderer* r = view.renderer();
  r->SetWorldPoint(p.x, p.y, p.z, 1);
  r->WorldToDisplay();
  const double* d = r->GetDisplayPoint();
  const double ratio = view.devicePixelRatioF();
  return QPoint(int(std::lround(d[0] / ratio)), int(std::lround((view.height() * ratio - d[1]) / ratio)));
}

TEST(GuiPlanning, TheDockReadsTheReamerAxisAndAimsTheReamer) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  QDockWidget* dock = planningDock(w);
  ASSERT_NE(dock, nullptr);
  ASSERT_TRUE(s.bone()->landmarks().complete()) << "the default case brings the bundled landmarks";
  auto* report = part<QLabel>(dock, "AxisAngles");
  ASSERT_NE(report, nullptr);
  const AxisAngles start = reamerAngles(s);
  EXPECT_TRUE(report->text().contains(QLocale().toString(start.versionDeg, 'f', 1) + "°")) << report->text().toStdString();
  EXPECT_TRUE(report->text().contains(QLocale().toString(start.inclinationDeg, 'f', 1) + "°")) << report->text().toStdString();

  auto* version = part<QDoubleSpinBox>(dock, "AimVersion");
  auto* inclination = part<QDoubleSpinBox>(dock, "AimInclination");
  auto* aim = part<QPushButton>(dock, "AimReamer");
  ASSERT_TRUE(version && inclination && aim);
  const std::size_t cutsBefore = s.cutsCommitted();
  const std::uint64_t revisionBefore = s.bone()->currentRevision();
  version->setValue(-10);
  inclination->setValue(5);
  QTest::mouseClick(aim, Qt::LeftButton);
  ASSERT_TRUE(s.waitIdle(60000));
  const AxisAngles aimed = reamerAngles(s);
  EXPECT_NEAR(aimed.versionDeg, -10, 1e-9);
  EXPECT_NEAR(aimed.inclinationDeg, 5, 1e-9);
  const Vec3 centre = *s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre];
  EXPECT_NEAR(norm(s.reamer()->pose().tip - centre), 10, 1e-9);
  // Placed clear of the bone: nothing cut, the next move starts there.
  EXPECT_EQ(s.cutsCommitted(), cutsBefore);
  EXPECT_EQ(s.bone()->currentRevision(), revisionBefore);
  EXPECT_TRUE(report->text().contains(QLocale().toString(-10.0, 'f', 1) + "°")) << report->text().toStdString();
  EXPECT_TRUE(report->text().contains("retroversion")) << report->text().toStdString();
  // Aim planned the axis: through the glenoid centre, drawn in the view, the reamer on it.
  ASSERT_TRUE(s.bone()->plannedAxis());
  EXPECT_EQ(s.bone()->plannedAxis()->tip, centre);
  const AxisAngles planned = axisAngles(scapularFrame(s.bone()->landmarks()), s.bone()->plannedAxis()->axis * -1.0);
  EXPECT_NEAR(planned.versionDeg, -10, 1e-9);
  EXPECT_TRUE(f.window->view()->landmarksLayer().plannedAxisShown());
  auto* plan = part<QLabel>(dock, "PlannedAxis");
  EXPECT_TRUE(plan->text().contains("the reamer is " + QLocale().toString(0.0, 'f', 1) + "° off it")) << plan->text().toStdString();
  Pose tilted = s.reamer()->pose();
  tilted.axis = normalized(tilted.axis + Vec3{0.05, 0, 0});
  s.moveReamer(tilted);
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(plan->text().contains("the reamer is " + QLocale().toString(0.0, 'f', 1) + "° off it")) << plan->text().toStdString();
  QTest::mouseClick(part<QPushButton>(dock, "ClearPlannedAxis"), Qt::LeftButton);
  EXPECT_FALSE(s.bone()->plannedAxis());
  QCoreApplication::processEvents();
  EXPECT_FALSE(f.window->view()->landmarksLayer().plannedAxisShown());

  // "Take the reamer's" reads the angles back into the fields (the reamer's now, tilted off the plan above).
  version->setValue(0);
  inclination->setValue(0);
  QTest::mouseClick(part<QPushButton>(dock, "TakeReamerAngles"), Qt::LeftButton);
  const AxisAngles now = reamerAngles(s);
  EXPECT_NEAR(version->value(), now.versionDeg, 0.05);
  EXPECT_NEAR(inclination->value(), now.inclinationDeg, 0.05);
  EXPECT_GT(std::abs(now.versionDeg + 10) + std::abs(now.inclinationDeg - 5), 0.5);
}

// Aim with the reamer's tip asked at the glenoid centre (no clearance): there the reamer overlaps the glenoid, and a
// placement would cut it. It is placed out along the aimed axis instead, as near as it is clear, and says so;
// nothing is cut.
// The glenoid face's angles of a state of the cut bone, as the dock measures them (about the glenoid centre).
AxisAngles glenoidAnglesOf(ReamSession& s, const BoneState& state) {
  const ScapulaLandmarks& marks = s.bone()->landmarks();
  return axisAngles(scapularFrame(marks), measureGlenoidFace(state, *marks[ScapulaLandmark::GlenoidCentre]).outward);
}

QString anglesShown(const AxisAngles& a) {
  return "version " + QLocale().toString(a.versionDeg, 'f', 1) + "°" + QString::fromUtf8(" (");
}

TEST(GuiPlanning, TheDockMeasuresTheGlenoidFaceAsOpenedAndAsReamed) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  QDockWidget* dock = planningDock(w);
  ASSERT_NE(dock, nullptr);
  auto* glenoid = part<QLabel>(dock, "GlenoidFace");
  ASSERT_NE(glenoid, nullptr);
  ASSERT_EQ(s.bone()->history().size(), 1u) << "the default case opens uncut";
  // Measured on a worker: the label says so until the answer comes.
  ASSERT_TRUE(QTest::qWaitFor([&] { return glenoid->text().contains("as opened"); }, 10000)) << glenoid->text().toStdString();
  const AxisAngles opened = glenoidAnglesOf(s, s.bone()->history().entries().front().state);
  EXPECT_TRUE(glenoid->text().contains(anglesShown(opened))) << glenoid->text().toStdString();
  EXPECT_TRUE(glenoid->text().contains(QLocale().toString(opened.inclinationDeg, 'f', 1) + "°")) << glenoid->text().toStdString();
  EXPECT_FALSE(glenoid->text().contains("now")) << "nothing cut yet: " << glenoid->text().toStdString();
  // The view draws the face's direction out of the glenoid centre (cyan), beside the planned axis.
  const ScapulaLandmarks marks = s.bone()->landmarks();
  const std::optional<Vec3> drawn = w.view()->landmarksLayer().glenoidAxisShown();
  ASSERT_TRUE(drawn);
  EXPECT_EQ(*drawn, measureGlenoidFace(s.bone()->history().entries().front().state,
                                       *marks[ScapulaLandmark::GlenoidCentre]).outward);
  s.bone()->setLandmark(ScapulaLandmark::GlenoidCentre, std::nullopt);
  QCoreApplication::processEvents();
  EXPECT_FALSE(w.view()->landmarksLayer().glenoidAxisShown());
  s.bone()->setLandmarks(marks);
  QCoreApplication::processEvents();
  ASSERT_TRUE(w.view()->landmarksLayer().glenoidAxisShown());
  EXPECT_EQ(*w.view()->landmarksLayer().glenoidAxisShown(), *drawn);

  // "Take the glenoid's" fills in its angles; Aim along them, and the plan says it corrects nothing.
  auto* version = part<QDoubleSpinBox>(dock, "AimVersion");
  auto* inclination = part<QDoubleSpinBox>(dock, "AimInclination");
  auto* takeGlenoid = part<QPushButton>(dock, "TakeGlenoidAngles");
  ASSERT_TRUE(version && inclination && takeGlenoid);
  ASSERT_TRUE(takeGlenoid->isEnabled());
  QTest::mouseClick(takeGlenoid, Qt::LeftButton);
  EXPECT_NEAR(version->value(), opened.versionDeg, 0.05 + 1e-9);
  EXPECT_NEAR(inclination->value(), opened.inclinationDeg, 0.05 + 1e-9);
  version->setValue(opened.versionDeg + 5);  // five degrees more anteversion than the glenoid's
  QTest::mouseClick(part<QPushButton>(dock, "AimReamer"), Qt::LeftButton);
  ASSERT_TRUE(s.waitIdle(60000));
  auto* plan = part<QLabel>(dock, "PlannedAxis");
  const AxisAngles planned = axisAngles(scapularFrame(s.bone()->landmarks()), s.bone()->plannedAxis()->axis * -1.0);
  EXPECT_TRUE(plan->text().contains("from the glenoid face as opened: +" +
                                    QLocale().toString(planned.versionDeg - opened.versionDeg, 'f', 1) + "° of version"))
      << plan->text().toStdString();

  // Reamed along the plan: the face as it is now joins the one as opened, and turns towards the reamer's axis.
  cutPastContact(s, s.reamer()->pose(), 2.0);
  ASSERT_GT(s.bone()->history().size(), 1u);
  ASSERT_TRUE(QTest::qWaitFor([&] { return glenoid->text().contains("as it is now: version") &&
                                            !glenoid->text().contains("updating"); }, 10000))
      << glenoid->text().toStdString();
  const AxisAngles now = glenoidAnglesOf(s, s.bone()->current());
  EXPECT_TRUE(glenoid->text().contains("as it is now: " + anglesShown(now))) << glenoid->text().toStdString();
  EXPECT_LT(std::abs(now.versionDeg - planned.versionDeg), std::abs(opened.versionDeg - planned.versionDeg));
  // Undone: as opened only, at once (both states were measured already).
  s.undoStack()->undo();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(glenoid->text().contains("now")) << glenoid->text().toStdString();
  EXPECT_TRUE(glenoid->text().contains(anglesShown(opened))) << glenoid->text().toStdString();
}

// Reaming cut after cut: the face as opened stays shown (its answer is kept however many cuts come), and the face
// now never falls back to "measuring" (the last cut's answer, marked "updating", until the newest cut's comes).
TEST(GuiPlanning, TheGlenoidFaceAsOpenedStaysThroughManyCuts) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  QDockWidget* dock = planningDock(*f.window);
  ASSERT_NE(dock, nullptr);
  auto* glenoid = part<QLabel>(dock, "GlenoidFace");
  ASSERT_TRUE(QTest::qWaitFor([&] { return glenoid->text().contains("as opened"); }, 10000)) << glenoid->text().toStdString();
  const QString opened = anglesShown(glenoidAnglesOf(s, s.bone()->history().entries().front().state));
  for (int i = 1; i <= 24; ++i) {
    cutOnce(s, 0.1 * i);
    EXPECT_TRUE(glenoid->text().contains("as opened: " + opened)) << "cut " << i << ": " << glenoid->text().toStdString();
    if (i > 1) {
      EXPECT_FALSE(glenoid->text().contains("as it is now: measuring")) << "cut " << i;
    }
  }
  ASSERT_TRUE(QTest::qWaitFor([&] { return !glenoid->text().contains("updating"); }, 10000));
  EXPECT_TRUE(glenoid->text().contains("as it is now: " + anglesShown(glenoidAnglesOf(s, s.bone()->current()))))
      << glenoid->text().toStdString();
  // Measured once: its answer was never dropped for the cuts' (24 of them, more than the answers kept).
  EXPECT_EQ(dock->property("glenoidOpenedMeasures").toInt(), 1);
}

TEST(GuiPlanning, AimPlacesTheReamerClearOfTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  QDockWidget* dock = planningDock(w);
  ASSERT_NE(dock, nullptr);
  auto* clearance = part<QDoubleSpinBox>(dock, "AimClearance");
  auto* aim = part<QPushButton>(dock, "AimReamer");
  ASSERT_TRUE(clearance && aim);
  const std::uint64_t revisionBefore = s.bone()->currentRevision();
  const std::size_t rowsBefore = s.log()->size();
  clearance->setValue(0);
  double retreat = -1;
  const QMetaObject::Connection c = QObject::connect(&s, &ReamSession::placedOutward, [&](double mm) { retreat = mm; });
  QTest::mouseClick(aim, Qt::LeftButton);
  // Until the placement has found its room, moves and feeds that start from the reamer are not taken (they would
  // start from the pose asked, in the bone).
  ASSERT_TRUE(s.placingClearOfBone());
  w.applyMove(ReamerMove::FeedForward);
  w.reamToDepth(1.0);
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("Aim is placing the reamer")) << w.statusBar()->currentMessage().toStdString();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_FALSE(s.placingClearOfBone());
  QObject::disconnect(c);
  ASSERT_GT(retreat, 0.1);
  EXPECT_LT(retreat, 30.0);
  EXPECT_EQ(s.bone()->currentRevision(), revisionBefore);  // nothing cut
  EXPECT_EQ(s.log()->size(), rowsBefore);
  const Vec3 centre = *s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre];
  EXPECT_NEAR(norm(s.reamer()->pose().tip - centre), retreat, 1e-6);  // on the aimed axis, that far out
  EXPECT_NEAR(dot(normalized(s.reamer()->pose().tip - centre), s.reamer()->pose().axis), -1.0, 1e-9);
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("further out along the axis than asked"))
      << w.statusBar()->currentMessage().toStdString();
  ASSERT_TRUE(s.path().size() >= 1);
  EXPECT_NEAR(norm(s.path().back().pose.tip - s.reamer()->pose().tip), 0.0, 1e-12);  // the path records where it went
  // A feed from there starts at the first contact (no cut on the way), and cuts.
  const Pose placed = s.reamer()->pose();
  const double approach = *advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), placed, 100);
  EXPECT_GT(approach, 0.0);  // clear
  EXPECT_LT(approach, 0.1);  // just outside: the margin

  // Asked 40 mm deep in the scapula's neck: back out to the nearest clear pose, the glenoid's, not cut through.
  s.placeClearOfBone(advancedAlongAxis(placed, 40.0));
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.bone()->currentRevision(), revisionBefore);
  EXPECT_NEAR(norm(s.reamer()->pose().tip - placed.tip), 0.0, 0.01);

  // Undone while it searches (the bone it searched is gone): nothing placed, the reamer back where it was computed,
  // not left at the pose asked, in the bone. Undone before it started (waiting for a frame): it searches the bone
  // as the undo left it, and places the reamer clear of that.
  for (const bool started : {true, false}) {
    cutOnce(s);
    const Pose cutPose = s.reamer()->pose();
    const Pose asked = advancedAlongAxis(cutPose, 3.0);
    s.setFrameGate(!started);  // without the gate the job starts at once
    bool dropped = false;
    const QMetaObject::Connection d =
        QObject::connect(&s, &ReamSession::notPlacedClearOfBone, [&](bool, bool wasDropped) { dropped = wasDropped; });
    s.placeClearOfBone(asked);
    EXPECT_EQ(s.busy(), true);
    s.undoStack()->undo();
    ASSERT_TRUE(s.waitIdle(60000));
    QObject::disconnect(d);
    EXPECT_EQ(s.bone()->currentRevision(), revisionBefore) << started;  // the cut undone, nothing cut since
    if (started) {
      EXPECT_NEAR(norm(s.reamer()->pose().tip - cutPose.tip), 0.0, 1e-12);
      EXPECT_TRUE(dropped);
    } else {
      const std::optional<double> gap =
          advanceToContactMm(s.bone()->current(), *s.reamer()->cuttingVolume(), s.reamer()->pose(), 100);
      ASSERT_TRUE(gap);
      EXPECT_GT(*gap, 0.0);  // clear of the bone now
      EXPECT_GT(norm(s.reamer()->pose().tip - asked.tip), 2.0);
    }
  }
  s.setFrameGate(true);
  // (Nothing clear within reach leaves the reamer where it was: ClearPlacement.NoRoomWithinReachPlacesNothing.)
}

TEST(GuiPlanning, AClickOnTheBonePlacesTheLandmarkAskedFor) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  BoneView& view = *w.view();
  QDockWidget* dock = planningDock(w);
  ASSERT_NE(dock, nullptr);
  const ScapulaLandmarks bundled = s.bone()->landmarks();
  const Vec3 centre = *bundled[ScapulaLandmark::GlenoidCentre];
  s.bone()->setLandmarks({});
  QCoreApplication::processEvents();
  EXPECT_FALSE(view.landmarksLayer().shown(ScapulaLandmark::GlenoidCentre));
  EXPECT_TRUE(part<QLabel>(dock, "AxisAngles")->text().contains("need the landmarks"));
  auto* place = part<QPushButton>(dock, "PlaceLandmark_glenoid_centre");
  ASSERT_NE(place, nullptr);
  QTest::mouseClick(place, Qt::LeftButton);
  EXPECT_EQ(s.interaction()->placeRequest(), ScapulaLandmark::GlenoidCentre);
  EXPECT_TRUE(place->isChecked());

  // A click beside the bone places nothing and does not turn the view, even dragged (a left drag turns it
  // otherwise): the request waits.
  vtkCamera* camera = view.renderer()->GetActiveCamera();
  double before[3], after[3];
  camera->GetDirectionOfProjection(before);
  const QPoint corner(3, view.height() - 3), dragged = corner + QPoint(80, -40);
  QTest::mousePress(&view, Qt::LeftButton, {}, corner);
  QMouseEvent move(QEvent::MouseMove, dragged, view.mapToGlobal(dragged), Qt::NoButton, Qt::LeftButton, {});
  QApplication::sendEvent(&view, &move);
  QTest::mouseRelease(&view, Qt::LeftButton, {}, dragged);
  camera->GetDirectionOfProjection(after);
  EXPECT_FALSE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
  EXPECT_EQ(s.interaction()->placeRequest(), ScapulaLandmark::GlenoidCentre);
  EXPECT_EQ(before[0], after[0]);
  EXPECT_EQ(before[1], after[1]);

  // A click where the glenoid centre is drawn places it there, on the bone's surface.
  const QPoint at = widgetPointOf(view, centre);
  ASSERT_TRUE(view.rect().contains(at));
  QTest::mouseClick(&view, Qt::LeftButton, {}, at);
  const std::optional<Vec3> placed = s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre];
  ASSERT_TRUE(placed);
  EXPECT_LT(norm(*placed - centre), 1.0);  // within the pixel's footprint of the bundled point
  EXPECT_FALSE(s.interaction()->placeRequest());
  EXPECT_FALSE(place->isChecked());
  EXPECT_TRUE(view.landmarksLayer().shown(ScapulaLandmark::GlenoidCentre));
  EXPECT_TRUE(part<QLabel>(dock, "LandmarkPoint_glenoid_centre")->text().contains(QLocale().toString(placed->x, 'f', 1)));
  EXPECT_EQ(s.bone()->landmarks().side, BodySide::Unspecified);  // the bundled bone names no patient frame

  // In a known patient frame the side follows once the scapular axis is placed: the bundled scapula's axis
  // points to +x, the patient's left in LPS.
  s.bone()->setPatientFrame(PatientFrame::LPS);
  s.bone()->setLandmarks({});
  s.bone()->setLandmark(ScapulaLandmark::TrigonumScapulae, bundled[ScapulaLandmark::TrigonumScapulae]);
  QTest::mouseClick(place, Qt::LeftButton);
  QTest::mouseClick(&view, Qt::LeftButton, {}, widgetPointOf(view, centre));
  EXPECT_TRUE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
  EXPECT_EQ(s.bone()->landmarks().side, BodySide::Left);
}

// Landmarks are work: placing one marks the window unsaved, Save writes them beside the bone
// (NAME.landmarks.json), opening the bone brings them back, and a save without any removes the file.
TEST(GuiPlanning, LandmarksAreSavedBesideTheBoneAndOpenWithIt) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  ASSERT_FALSE(w.hasUnsavedChanges());  // the bundled landmarks come with the bundled bone
  Vec3 centre = *s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre];
  centre.z += 1.25;
  s.bone()->setLandmark(ScapulaLandmark::GlenoidCentre, centre);
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_TRUE(w.isWindowModified());
  const ScapulaLandmarks placed = s.bone()->landmarks();
  const Pose plannedAxis{centre, {0, -1, 0}, 0};
  s.bone()->setPlannedAxis(plannedAxis);
  const QString bonePath = dir.filePath("scapula.ply");
  ASSERT_TRUE(w.saveBoneAs(bonePath)) << w.lastError().toStdString();
  const QString beside = dir.filePath("scapula.ply.landmarks.json");
  ASSERT_TRUE(QFileInfo::exists(beside));
  EXPECT_EQ(loadLandmarks(beside.toStdString()), placed);
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_FALSE(w.isWindowModified());

  w.openFile(bonePath, true);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w.windowTitle().contains("scapula.ply"); }, 60000)) << w.lastError().toStdString();
  EXPECT_EQ(s.bone()->landmarks(), placed);
  ASSERT_TRUE(s.bone()->plannedAxis());
  EXPECT_EQ(s.bone()->plannedAxis()->axis, plannedAxis.axis);
  EXPECT_FALSE(w.hasUnsavedChanges());
  s.bone()->setPlannedAxis(std::nullopt);  // the plan alone is work too
  EXPECT_TRUE(w.hasUnsavedChanges());
  s.bone()->setPlannedAxis(plannedAxis);
  EXPECT_FALSE(w.hasUnsavedChanges());

  s.bone()->setLandmarks({});
  s.bone()->setPlannedAxis(std::nullopt);
  EXPECT_TRUE(w.hasUnsavedChanges());
  ASSERT_TRUE(w.saveBoneAs(bonePath));
  EXPECT_FALSE(QFileInfo::exists(beside));  // would bring the cleared points back on the next open

  // A file beside that cannot be read is named, and a save keeps it aside instead of replacing it.
  const std::string damaged = R"({"side": "right", "glenoid_center": [1, 2, 3]})";
  writeTextFile(beside.toStdString(), damaged);
  w.openFile(bonePath, true);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w.lastError().contains("glenoid_center"); }, 60000)) << w.lastError().toStdString();
  EXPECT_TRUE(w.lastError().contains(beside)) << w.lastError().toStdString();
  EXPECT_FALSE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
  s.bone()->setLandmarks(placed);
  ASSERT_TRUE(w.saveBoneAs(bonePath));
  EXPECT_EQ(loadLandmarks(beside.toStdString()), placed);
  QFile kept(beside + ".unreadable");
  ASSERT_TRUE(kept.open(QIODevice::ReadOnly));
  EXPECT_EQ(kept.readAll().toStdString(), damaged);  // as it was
}

// A landmark edit is undone by Ctrl+Z like a cut, in the order they were made, and neither stops the steps
// running nor counts as a change of the bone; landmarks that come with a bone are not edits.
TEST(GuiPlanning, LandmarkEditsAreOnTheUndoStackBesideTheCuts) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  ReamSession& s = f.session();
  QUndoStack& undo = *s.undoStack();
  EXPECT_EQ(undo.count(), 0);  // the bundled landmarks came with the bone
  const ScapulaLandmarks bundled = s.bone()->landmarks();
  cutOnce(s);
  ASSERT_EQ(undo.count(), 1);
  const std::uint64_t cut = s.bone()->currentRevision();
  Vec3 centre = *bundled[ScapulaLandmark::GlenoidCentre];
  centre.y += 2;
  s.bone()->setLandmark(ScapulaLandmark::GlenoidCentre, centre);  // as a click in the view places it
  ASSERT_EQ(undo.count(), 2);
  EXPECT_EQ(undo.text(1), "Place the glenoid centre");
  const Pose axis{centre, {0, -1, 0}, 0};
  s.bone()->setPlannedAxis(axis);  // Aim
  EXPECT_EQ(undo.text(2), "Plan the axis");
  EXPECT_TRUE(w.hasUnsavedChanges());

  w.action("undo")->trigger();  // the plan
  EXPECT_FALSE(s.bone()->plannedAxis());
  w.action("undo")->trigger();  // the landmark
  EXPECT_EQ(s.bone()->landmarks(), bundled);
  EXPECT_EQ(s.bone()->currentRevision(), cut);  // the cut stays
  w.action("undo")->trigger();  // the cut
  EXPECT_NE(s.bone()->currentRevision(), cut);
  EXPECT_FALSE(w.hasUnsavedChanges());
  w.action("redo")->trigger();
  w.action("redo")->trigger();
  w.action("redo")->trigger();
  EXPECT_EQ(s.bone()->currentRevision(), cut);
  EXPECT_EQ(*s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre], centre);
  ASSERT_TRUE(s.bone()->plannedAxis());

  // Saved, then only landmark edits undone and redone: the bone itself is as saved; the title follows the landmarks.
  QTemporaryDir dir;
  ASSERT_TRUE(w.saveBoneAs(dir.filePath("bone.ply"))) << w.lastError().toStdString();
  s.bone()->setPlannedAxis(std::nullopt);
  EXPECT_TRUE(w.hasUnsavedChanges());
  EXPECT_FALSE(w.boneChangedSinceSave());
  w.action("undo")->trigger();
  EXPECT_FALSE(w.hasUnsavedChanges());
  EXPECT_FALSE(w.isWindowModified());

  // A feed runs on while a landmark is placed, and while that is undone: neither interrupts the path.
  s.restartPath(ReamSession::PathStart::Changed);  // the cut undone above interrupted the one before
  const Pose seated = s.reamer()->pose();
  s.runSteps({advancedAlongAxis(seated, 0.1), advancedAlongAxis(seated, 0.2), advancedAlongAxis(seated, 0.3),
              advancedAlongAxis(seated, 0.4)});
  ASSERT_TRUE(s.busy());
  const std::size_t pathBefore = s.path().size();
  s.bone()->setLandmark(ScapulaLandmark::InferiorAngle, *bundled[ScapulaLandmark::InferiorAngle] + Vec3{0, 0, 1});
  w.action("undo")->trigger();
  ASSERT_TRUE(s.waitIdle(60000));
  EXPECT_EQ(s.path().size(), pathBefore + 4);  // every step ran
  EXPECT_FALSE(s.pathInterrupted());
  EXPECT_EQ(s.bone()->landmarks()[ScapulaLandmark::InferiorAngle], bundled[ScapulaLandmark::InferiorAngle]);

  // An edit while a cut can be redone is made but not recorded: the cut stays redoable.
  cutOnce(s, 1.2);
  const int commands = undo.count();
  w.action("undo")->trigger();
  ASSERT_TRUE(undo.canRedo());
  s.bone()->setLandmark(ScapulaLandmark::TrigonumScapulae, *bundled[ScapulaLandmark::TrigonumScapulae] + Vec3{1, 0, 0});
  EXPECT_EQ(undo.count(), commands);
  EXPECT_TRUE(undo.canRedo());
  EXPECT_TRUE(w.statusBar()->currentMessage().contains("Undo cannot take it back")) << w.statusBar()->currentMessage().toStdString();
  w.action("redo")->trigger();
  EXPECT_FALSE(undo.canRedo());
  s.bone()->setLandmark(ScapulaLandmark::TrigonumScapulae, *bundled[ScapulaLandmark::TrigonumScapulae]);  // recorded again
  EXPECT_EQ(undo.count(), commands + 1);

  // The title follows the bone through undo and redo when landmark edits lie between the save and the cut.
  ASSERT_TRUE(w.saveBoneAs(dir.filePath("bone.ply"))) << w.lastError().toStdString();
  s.bone()->setPlannedAxis(std::nullopt);
  s.bone()->setPlannedAxis(axis);  // as saved again
  EXPECT_FALSE(w.isWindowModified());
  cutOnce(s, 1.4);
  EXPECT_TRUE(w.isWindowModified());
  w.action("undo")->trigger();
  EXPECT_FALSE(w.isWindowModified());
  w.action("redo")->trigger();
  EXPECT_TRUE(w.isWindowModified());
  w.action("undo")->trigger();

  // Opening a bone with landmarks saved beside it: they are not an edit to undo.
  w.openFile(dir.filePath("bone.ply"), true);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w.windowTitle().contains("bone.ply"); }, 60000)) << w.lastError().toStdString();
  ASSERT_TRUE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
  // The stack holds the saved undo history's cuts (SavedHistory.h), and no landmark edit.
  EXPECT_EQ(undo.count(), int(s.bone()->history().size()) - 1);
  for (int i = 0; i < undo.count(); ++i) EXPECT_TRUE(undo.text(i).contains("before the save")) << undo.text(i).toStdString();
  EXPECT_FALSE(w.hasUnsavedChanges());
}

TEST(GuiPlanning, LandmarkFilesRoundTripAndADamagedOneIsNamed) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  QDockWidget* dock = planningDock(*f.window);
  ASSERT_NE(dock, nullptr);
  QTemporaryDir dir;
  const QString path = dir.filePath("marks.json");
  ScapulaLandmarks marks = s.bone()->landmarks();
  ASSERT_TRUE(QMetaObject::invokeMethod(dock, "saveLandmarksTo", Q_ARG(QString, path)));
  s.bone()->setLandmarks({});
  QString error;
  ASSERT_TRUE(QMetaObject::invokeMethod(dock, "loadLandmarksFrom", Q_RETURN_ARG(QString, error), Q_ARG(QString, path)));
  EXPECT_TRUE(error.isEmpty()) << error.toStdString();
  EXPECT_EQ(s.bone()->landmarks(), marks);

  const QString bad = dir.filePath("bad.json");
  std::ofstream(bad.toStdString()) << R"({"side": "right", "inferior_angle": [1, 2]})";
  ASSERT_TRUE(QMetaObject::invokeMethod(dock, "loadLandmarksFrom", Q_RETURN_ARG(QString, error), Q_ARG(QString, bad)));
  EXPECT_TRUE(error.contains(bad)) << error.toStdString();
  EXPECT_TRUE(error.contains("inferior_angle")) << error.toStdString();
  EXPECT_EQ(s.bone()->landmarks(), marks);  // a file that cannot be read changes nothing

  // Another bone: the points were placed on this one and go.
  ImportedBone box;
  box.mesh = loadDefaultBone().mesh;
  box.cuttable = true;
  s.loadBone(std::move(box), "again", s.reamer()->pose());
  EXPECT_FALSE(s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre]);
}

// The cut log shows each cut's version and inclination in the frame of the bone's landmarks, and follows them
// when they change.
TEST(GuiPlanning, TheCutLogShowsEachCutsVersionAndInclination) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  ReamSession& s = f.session();
  cutOnce(s);
  auto* table = f.window->findChild<QTableWidget*>("LogTable");
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rowCount(), 1);
  const int column = table->columnCount() - 2;  // before the notes
  EXPECT_EQ(table->horizontalHeaderItem(column)->text(), "version / inclination");
  const AxisAngles a = axisAngles(scapularFrame(s.bone()->landmarks()), s.log()->entries().front().pose.axis * -1.0);
  const QString expected = QLocale().toString(a.versionDeg, 'f', 1) + "° / " + QLocale().toString(a.inclinationDeg, 'f', 1) + "°";
  ASSERT_NE(table->item(0, column), nullptr);
  EXPECT_EQ(table->item(0, column)->text(), expected);
  const ScapulaLandmarks placed = s.bone()->landmarks();
  s.bone()->setLandmark(ScapulaLandmark::InferiorAngle, std::nullopt);
  EXPECT_EQ(table->item(0, column)->text(), "–");
  s.bone()->setLandmarks(placed);
  EXPECT_EQ(table->item(0, column)->text(), expected);

  // Export CSV… writes them too (version_deg, inclination_deg), and leaves them out without a frame.
  QTemporaryDir dir;
  auto* panel = f.window->findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  auto exported = [&](const QString& name) -> QStringList {
    QString error;
    EXPECT_TRUE(QMetaObject::invokeMethod(panel, "exportCsv", Q_RETURN_ARG(QString, error),
                                          Q_ARG(QString, dir.filePath(name)), Q_ARG(bool, false)));
    EXPECT_TRUE(error.isEmpty()) << error.toStdString();
    QFile file(dir.filePath(name));
    EXPECT_TRUE(file.open(QIODevice::ReadOnly));
    return QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
  };
  const QStringList withAngles = exported("angles.csv");
  ASSERT_EQ(withAngles.size(), 2);
  EXPECT_TRUE(withAngles[0].endsWith(",version_deg,inclination_deg"));
  const QStringList cells = withAngles[1].split(',');
  EXPECT_NEAR(cells[cells.size() - 2].toDouble(), a.versionDeg, 1e-6);
  EXPECT_NEAR(cells.back().toDouble(), a.inclinationDeg, 1e-6);
  s.bone()->setLandmark(ScapulaLandmark::InferiorAngle, std::nullopt);
  const QStringList plain = exported("plain.csv");
  ASSERT_FALSE(plain.isEmpty());
  EXPECT_TRUE(plain[0].endsWith(",undone,note"));
  EXPECT_EQ(readCutLogCsv(dir.filePath("angles.csv").toStdString()).size(), 1u);  // it reads back
}

// File → Export a report: one HTML file with what was removed, the landmarks' angles and the view's picture.
TEST(GuiPlanning, AReportHoldsTheRemovedVolumeTheAnglesAndThePicture) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  GuiFixture f;
  ReamSession& s = f.session();
  cutOnce(s);
  s.bone()->setPlannedAxis(Pose{*s.bone()->landmarks()[ScapulaLandmark::GlenoidCentre], s.reamer()->pose().axis, 0});
  cutOnce(s, 1.0);
  f.window->action("undo")->trigger();  // the second cut: logged, not in the bone
  ASSERT_TRUE(s.waitIdle(60000));
  const QString file = dir.filePath("report.html");
  const QString error = f.window->exportReport(file);
  ASSERT_TRUE(error.isEmpty()) << error.toStdString();
  QFile in(file);
  ASSERT_TRUE(in.open(QIODevice::ReadOnly));
  const QString html = QString::fromUtf8(in.readAll());
  const double removed = s.initialVolumeMm3() - s.bone()->current().volume();
  EXPECT_TRUE(html.contains("<b>" + QString::number(removed, 'f', 3) + " mm³</b>")) << removed;
  const AxisAngles a = reamerAngles(s);
  EXPECT_TRUE(html.contains(QString::number(a.versionDeg, 'f', 1) + "° (")) << a.versionDeg;
  EXPECT_TRUE(html.contains("trigonum scapulae"));
  EXPECT_TRUE(html.contains("Planned axis: version, inclination"));
  // The glenoid face as opened and as the bone is now (one cut of the two undone: the state after the first).
  const AxisAngles faceNow = glenoidAnglesOf(s, s.bone()->current());
  EXPECT_TRUE(html.contains("Glenoid face now: version, inclination</th><td>" +
                            QString::number(faceNow.versionDeg, 'f', 1) + "° (")) << faceNow.versionDeg;
  EXPECT_TRUE(html.contains("Glenoid face as opened: version, inclination"));
  EXPECT_TRUE(html.contains("Planned axis from the glenoid face as opened"));
  // The seat at the reamer's pose, as Measure seat says it.
  const ReamedSurfaceReport seat = measureReamedSurface(s.bone()->current().toMesh(), s.reamer()->spec(), s.reamer()->pose());
  EXPECT_TRUE(html.contains("Seat where the reamer is</th><td>" + QString::number(100 * seat.seatedFraction, 'f', 1) +
                            " % of the cutting face on bone")) << seat.seatedFraction;
  EXPECT_TRUE(html.contains("<th>off the plan</th>"));
  EXPECT_TRUE(html.contains("2 (1 undone: not in the bone now)")) << html.toStdString();
  EXPECT_EQ(html.count(" (undone)</td>"), 1);
  const QString marker = "data:image/png;base64,";
  const int at = html.indexOf(marker);
  ASSERT_GE(at, 0);
  const int end = html.indexOf('"', at);
  const QImage picture = QImage::fromData(QByteArray::fromBase64(html.mid(at + marker.size(), end - at - marker.size()).toLatin1()), "PNG");
  ASSERT_FALSE(picture.isNull());
  EXPECT_EQ(picture.width(), int(f.window->view()->width() * f.window->view()->devicePixelRatioF()));
  EXPECT_TRUE(f.window->exportReport(dir.filePath("no/such/dir/report.html")).contains("no/such/dir"));
}

}  // namespace
}  // namespace reamsim::ui::test
