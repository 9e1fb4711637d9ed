// The real window driven by key and mouse events; every check is on the shared document.
#include <vtkCamera.h>
#include <vtkRenderer.h>

#include <QAction>
#include <QDockWidget>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTableWidget>
#include <QUndoView>
#include <QtTest/QTest>
#include <cmath>

#include "GuiEnvironment.h"

namespace reamsim::ui::test {
namespace {

double angleDeg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(normalized(a), normalized(b)), -1.0, 1.0)) * 180.0 / M_PI;
}

int logRows(MainWindow& w) {
  auto* table = w.findChild<QTableWidget*>("LogTable");
  return table ? table->rowCount() : -1;
}

// Away from the bone (outside its bounding box), so key moves run the collision query but never cut.
void parkAwayFromBone(GuiFixture& f) {
  const Bounds b = f.session().bone()->current().bounds();
  f.session().moveReamer(Pose{{b.center().x, b.center().y, b.max.z + 40}, {0, 0, -1}, 0});
  ASSERT_TRUE(f.session().waitIdle(60000));
}

// Keys stored by an older version may since have been taken by a menu action (Ctrl+Shift+R: Choose the reamer…):
// such a key would work for neither, so the move keeps its default key and the status bar says why.
TEST(GuiWindow, AStoredKeyThatAMenuActionTookIsNotUsed) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  QTemporaryDir dir;
  QSettings stored(dir.filePath("keys.ini"), QSettings::IniFormat);
  stored.setValue("keys/move_x_plus", "Ctrl+Shift+R");
  stored.setValue("keys/move_y_plus", "Q");
  w.applyStoredKeyBindings(stored);
  EXPECT_EQ(w.action("reamer_move_x_plus")->shortcut(), QKeySequence("Right"));  // the default
  EXPECT_EQ(w.action("reamer_move_y_plus")->shortcut(), QKeySequence("Q"));
  EXPECT_EQ(w.action("choose_reamer")->shortcut(), QKeySequence("Ctrl+Shift+R"));
  const QString status = w.statusBar()->currentMessage();
  EXPECT_TRUE(status.contains("Move +X") && status.contains("Choose the reamer")) << status.toStdString();
}

TEST(GuiWindow, ThesisKeysMoveAndRotateTheReamer) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  parkAwayFromBone(f);
  MainWindow& w = *f.window;
  w.setSteps(0.5, 2.0, 0.2);
  const ReamerNode& reamer = *f.session().reamer();
  const Pose p0 = reamer.pose();

  QTest::keyClick(w.windowHandle(), Qt::Key_Right);
  EXPECT_NEAR(reamer.pose().tip.x - p0.tip.x, 0.5, 1e-12);
  QTest::keyClick(w.windowHandle(), Qt::Key_Up);
  EXPECT_NEAR(reamer.pose().tip.y - p0.tip.y, 0.5, 1e-12);
  QTest::keyClick(w.windowHandle(), Qt::Key_X);
  EXPECT_NEAR(reamer.pose().tip.z - p0.tip.z, 0.5, 1e-12);
  QTest::keyClick(w.windowHandle(), Qt::Key_Z);
  QTest::keyClick(w.windowHandle(), Qt::Key_Z);
  EXPECT_NEAR(reamer.pose().tip.z - p0.tip.z, -0.5, 1e-12);

  const Vec3 a0 = reamer.pose().axis;
  QTest::keyClick(w.windowHandle(), Qt::Key_A);  // about X: the X component stays
  EXPECT_NEAR(angleDeg(a0, reamer.pose().axis), 2.0, 1e-9);
  EXPECT_NEAR(reamer.pose().axis.x, a0.x, 1e-12);
  QTest::keyClick(w.windowHandle(), Qt::Key_S);  // and back
  EXPECT_NEAR(angleDeg(a0, reamer.pose().axis), 0.0, 1e-6);
  QTest::keyClick(w.windowHandle(), Qt::Key_R);  // about Y
  EXPECT_NEAR(angleDeg(a0, reamer.pose().axis), 2.0, 1e-9);
  EXPECT_NEAR(reamer.pose().axis.y, a0.y, 1e-12);

  // A key another action has is refused (W toggles the wireframe; a shared key would work for neither).
  EXPECT_FALSE(w.setKeyBinding(ReamerMove::XPlus, QKeySequence("W")));
  EXPECT_TRUE(w.lastError().contains("Wireframe")) << w.lastError().toStdString();
  EXPECT_EQ(w.moveAction(ReamerMove::XPlus)->shortcut(), QKeySequence(Qt::Key_Right));
  EXPECT_FALSE(w.setKeyBinding(ReamerMove::XPlus, QKeySequence("Left")));  // the -X move's key
  for (QMessageBox* box : w.findChildren<QMessageBox*>("ErrorDialog")) box->close();
  w.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&w));
  // Remapped: L now moves +X, the right arrow does nothing.
  EXPECT_TRUE(w.setKeyBinding(ReamerMove::XPlus, QKeySequence("L")));
  const double x = reamer.pose().tip.x;
  QTest::keyClick(w.windowHandle(), Qt::Key_Right);
  EXPECT_EQ(reamer.pose().tip.x, x);
  QTest::keyClick(w.windowHandle(), Qt::Key_L);
  EXPECT_NEAR(reamer.pose().tip.x - x, 0.5, 1e-12);
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().cutsCommitted(), 0u);
  EXPECT_EQ(w.statusAlertText(), "clear");
}

TEST(GuiWindow, ContactCutsLogsAndUndoRestoresTheBoneExactly) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;  // the default case: the reamer waits 2 mm lateral of the glenoid
  MainWindow& w = *f.window;
  BoneNode& bone = *f.session().bone();
  const TriangleMesh before = bone.current().toMesh();
  const double volumeBefore = bone.current().volume();
  EXPECT_EQ(logRows(w), 0);

  w.setSteps(0.5, 2.0, 2.5);                          // one feed step of 2.5 mm: 0.5 mm into the glenoid
  QTest::keyClick(w.windowHandle(), Qt::Key_PageDown);  // "feed along axis"
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().cutsCommitted(), 1u);
  EXPECT_TRUE(f.session().alerts()->has(AlertKind::Contact));
  EXPECT_EQ(w.statusAlertText(), "CONTACT");
  const double removed = volumeBefore - bone.current().volume();
  EXPECT_GT(removed, 1.0);
  ASSERT_EQ(logRows(w), 1);
  EXPECT_NEAR(f.session().log()->last().removedMm3, removed, 1e-6 * removed);
  EXPECT_TRUE(f.session().log()->last().contactPoint.has_value());
  EXPECT_GT(w.view()->freshTriangleCount(), 0u);  // the new surface is highlighted
  auto* history = w.findChild<QUndoView*>("HistoryView");
  ASSERT_NE(history, nullptr);
  EXPECT_EQ(history->model()->rowCount(), 2);  // the imported bone + one cut
  const TriangleMesh after = bone.current().toMesh();

  QTest::keyClick(w.windowHandle(), Qt::Key_Z, Qt::ControlModifier);
  EXPECT_EQ(bone.current().toMesh().vertices, before.vertices);
  EXPECT_EQ(bone.current().toMesh().triangles, before.triangles);
  EXPECT_EQ(bone.current().volume(), volumeBefore);
  EXPECT_EQ(w.view()->freshTriangleCount(), 0u);
  QTest::keyClick(w.windowHandle(), Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
  EXPECT_EQ(bone.current().toMesh().triangles, after.triangles);
  EXPECT_EQ(logRows(w), 1);  // the log records what was done; undo does not erase rows
}

TEST(GuiWindow, MouseFollowsTheThesisAndCtrlDragFeedsAlongTheAxis) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  parkAwayFromBone(f);
  BoneView* view = f.window->view();
  vtkCamera* cam = view->renderer()->GetActiveCamera();
  EXPECT_TRUE(cam->GetParallelProjection());  // orthographic
  const QPoint c = view->rect().center();
  auto drag = [&](Qt::MouseButton button, Qt::KeyboardModifiers mods, QPoint to) {
    QTest::mousePress(view, button, mods, c);
    QMouseEvent move(QEvent::MouseMove, to, view->mapToGlobal(to), Qt::NoButton, button, mods);
    QApplication::sendEvent(view, &move);
    QTest::mouseRelease(view, button, mods, to);
  };

  double dop0[3], dop1[3];
  cam->GetDirectionOfProjection(dop0);
  drag(Qt::LeftButton, Qt::NoModifier, c + QPoint(60, 0));  // left: rotate
  cam->GetDirectionOfProjection(dop1);
  EXPECT_GT(std::abs(dop0[0] - dop1[0]) + std::abs(dop0[1] - dop1[1]) + std::abs(dop0[2] - dop1[2]), 1e-3);

  const double scale0 = cam->GetParallelScale();
  drag(Qt::MiddleButton, Qt::NoModifier, c + QPoint(0, -60));  // middle: zoom
  EXPECT_NE(cam->GetParallelScale(), scale0);

  double f0[3], f1[3];
  cam->GetFocalPoint(f0);
  drag(Qt::RightButton, Qt::NoModifier, c + QPoint(40, 30));  // right: pan
  cam->GetFocalPoint(f1);
  EXPECT_GT(std::abs(f0[0] - f1[0]) + std::abs(f0[1] - f1[1]) + std::abs(f0[2] - f1[2]), 1e-3);
  EXPECT_EQ(cam->GetParallelScale() > 0, true);

  // Ctrl + left drag: the reamer moves along its own axis, the camera does not turn.
  const Pose p0 = f.session().reamer()->pose();
  cam->GetDirectionOfProjection(dop0);
  drag(Qt::LeftButton, Qt::ControlModifier, c + QPoint(25, -45));
  cam->GetDirectionOfProjection(dop1);
  const Vec3 moved = f.session().reamer()->pose().tip - p0.tip;
  EXPECT_GT(norm(moved), 0.05);
  EXPECT_LT(norm(cross(moved, p0.axis)), 1e-9 * std::max(1.0, norm(moved)));  // along the axis only
  EXPECT_NEAR(dop0[0], dop1[0], 1e-12);
  EXPECT_NEAR(dop0[1], dop1[1], 1e-12);
  ASSERT_TRUE(f.session().waitIdle(60000));
}

TEST(GuiWindow, StandardViewsLookAlongTheirAxes) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  vtkCamera* cam = f.window->view()->renderer()->GetActiveCamera();
  double d[3];
  f.window->action("view_anterior")->trigger();
  cam->GetDirectionOfProjection(d);
  EXPECT_NEAR(d[0], -1.0, 1e-9);
  f.window->action("view_superior")->trigger();
  cam->GetDirectionOfProjection(d);
  EXPECT_NEAR(d[1], -1.0, 1e-9);
  f.window->action("view_en_face")->trigger();  // along the planned axis
  cam->GetDirectionOfProjection(d);
  const Vec3 axis = normalized(f.session().plan()->poses().front().axis);
  EXPECT_NEAR(dot(Vec3{d[0], d[1], d[2]}, axis), 1.0, 1e-9);
  EXPECT_TRUE(cam->GetParallelProjection());
}

}  // namespace
}  // namespace reamsim::ui::test
