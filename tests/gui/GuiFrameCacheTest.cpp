// Frames where only the reamer moved reuse the bone's picture (ui/CachedBoneLayer.h). They must look exactly
// like frames drawn in full, and the bone must be drawn again whenever what it shows changes.
#include <vtkCamera.h>
#include <vtkRenderer.h>

#include <QImage>
#include <functional>
#include <QtTest/QTest>

#include "CachedBoneLayer.h"
#include "GuiEnvironment.h"

namespace reamsim::ui::test {
namespace {

// Pixels whose colour differs by more than `tolerance` in some channel.
int differingPixels(const QImage& a, const QImage& b, int tolerance = 1) {
  if (a.size() != b.size()) return a.width() * a.height() + 1;
  const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
  int n = 0;
  for (int r = 0; r < x.height(); ++r) {
    const QRgb* p = reinterpret_cast<const QRgb*>(x.constScanLine(r));
    const QRgb* q = reinterpret_cast<const QRgb*>(y.constScanLine(r));
    for (int c = 0; c < x.width(); ++c)
      if (std::abs(qRed(p[c]) - qRed(q[c])) > tolerance || std::abs(qGreen(p[c]) - qGreen(q[c])) > tolerance ||
          std::abs(qBlue(p[c]) - qBlue(q[c])) > tolerance)
        ++n;
  }
  return n;
}

// Renders now (VTK draws at render(); grabFramebuffer() reads what was drawn last) and reads the frame.
QImage frame(BoneView& view) {
  view.render();
  return view.grabFramebuffer();
}

QImage fullFrame(BoneView& view) {
  view.setBoneCacheEnabled(false);  // renders in full
  const QImage image = view.grabFramebuffer();
  view.setBoneCacheEnabled(true);
  return image;
}

TEST(GuiFrameCache, ReamerMovesReuseTheBoneAndLookLikeFullFrames) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  BoneView& view = *w.view();
  ASSERT_TRUE(view.boneCache().disabledReason().empty()) << view.boneCache().disabledReason();
  // In front of the glenoid, partly hidden by the bone in the anterior view: depth matters.
  const Pose start = f.session().plan()->poses().front();
  f.session().moveReamer(start);
  ASSERT_TRUE(f.session().waitIdle(60000));
  view.setStandardView(BoneView::StandardView::Anterior);
  w.setSteps(2.0, 2.0, 0.2);
  (void)frame(view);  // the bone drawn for this view

  const std::size_t reusedBefore = view.boneCache().reusedFrames();
  for (Qt::Key key : {Qt::Key_Up, Qt::Key_Z, Qt::Key_Down}) {  // Y and Z: across the anterior view
    QTest::keyClick(w.windowHandle(), key);
    ASSERT_TRUE(f.session().waitIdle(60000));
    (void)frame(view);
  }
  EXPECT_GE(view.boneCache().reusedFrames(), reusedBefore + 3) << "reamer moves must not redraw the bone";
  EXPECT_TRUE(view.boneCache().disabledReason().empty()) << view.boneCache().disabledReason();

  const QImage cached = frame(view);
  const QImage full = fullFrame(view);
  ASSERT_FALSE(cached.isNull());
  EXPECT_EQ(differingPixels(cached, full), 0);
  // The picture is not trivially the same: moving the reamer changes it.
  QTest::keyClick(w.windowHandle(), Qt::Key_Up);
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_GT(differingPixels(frame(view), cached), 50);
}

TEST(GuiFrameCache, CameraColourAndBoneChangesRedrawTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  BoneView& view = *w.view();
  f.session().moveReamer(f.session().plan()->poses().front());
  ASSERT_TRUE(f.session().waitIdle(60000));
  (void)frame(view);

  auto expectRedrawnAndEqualToFull = [&](const char* what, const std::function<void()>& change) {
    const std::size_t drawn = view.boneCache().drawnFrames();
    change();
    (void)frame(view);
    EXPECT_GT(view.boneCache().drawnFrames(), drawn) << what;
    const QImage cached = frame(view);  // now reused
    EXPECT_EQ(differingPixels(cached, fullFrame(view)), 0) << what;
  };
  expectRedrawnAndEqualToFull("camera turned", [&] { view.renderer()->GetActiveCamera()->Azimuth(25); });
  expectRedrawnAndEqualToFull("depth colours", [&] { view.setColourMode(BoneView::ColourMode::Depth); });
  expectRedrawnAndEqualToFull("surface colours", [&] { view.setColourMode(BoneView::ColourMode::Surface); });
  expectRedrawnAndEqualToFull("wireframe", [&] { view.setWireframe(true); });
  expectRedrawnAndEqualToFull("no wireframe", [&] { view.setWireframe(false); });
  expectRedrawnAndEqualToFull("window resized", [&] { w.resize(w.width() - 40, w.height() - 30); QTest::qWait(50); });

  // A cut changes the bone: the next frame draws it, and shows the cut.
  const QImage before = frame(view);
  const std::size_t drawn = view.boneCache().drawnFrames();
  w.feedBy(2.0);
  ASSERT_TRUE(f.session().waitIdle(120000));
  ASSERT_GT(f.session().log()->size(), 0u);
  const QImage after = frame(view);
  EXPECT_GT(view.boneCache().drawnFrames(), drawn);
  EXPECT_GT(differingPixels(after, before), 50);
  EXPECT_EQ(differingPixels(frame(view), fullFrame(view)), 0);
}

}  // namespace
}  // namespace reamsim::ui::test
