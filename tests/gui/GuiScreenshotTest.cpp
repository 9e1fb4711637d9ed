// Screenshot regression: the 3D view after a few cuts of the default case, against tests/baselines/ with
// a tolerant diff (llvmpipe is deterministic, fonts and drivers may differ a little elsewhere).
// REAMSIM_UPDATE_BASELINES=1 rewrites the baseline (and fails, so that it is never silently accepted).
#include <vtkCamera.h>
#include <vtkRenderer.h>

#include <QAction>
#include <QDir>
#include <QImage>
#include <cstdlib>

#include "GuiEnvironment.h"

namespace reamsim::ui::test {
namespace {

struct ImageDiff {
  double meanAbs = 0;        // mean |difference| per channel, 0..255
  double differingShare = 0;  // share of pixels with a channel differing by more than 40
};

ImageDiff compare(const QImage& a, const QImage& b) {
  ImageDiff d;
  const QImage x = a.convertToFormat(QImage::Format_RGB32), y = b.convertToFormat(QImage::Format_RGB32);
  double sum = 0;
  long differing = 0;
  for (int row = 0; row < x.height(); ++row) {
    const QRgb* p = reinterpret_cast<const QRgb*>(x.constScanLine(row));
    const QRgb* q = reinterpret_cast<const QRgb*>(y.constScanLine(row));
    for (int col = 0; col < x.width(); ++col) {
      const int dr = std::abs(qRed(p[col]) - qRed(q[col])), dg = std::abs(qGreen(p[col]) - qGreen(q[col])),
                db = std::abs(qBlue(p[col]) - qBlue(q[col]));
      sum += dr + dg + db;
      differing += std::max({dr, dg, db}) > 40;
    }
  }
  const double pixels = double(x.width()) * x.height();
  d.meanAbs = sum / (3 * pixels);
  d.differingShare = differing / pixels;
  return d;
}

TEST(GuiScreenshot, ReamedGlenoidMatchesTheBaseline) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  BoneView* view = w.view();
  view->setFixedSize(640, 480);
  w.setSteps(0.5, 2.0, 0.5);
  w.feedBy(3.5);  // 7 feed steps of 0.5 mm from 2 mm lateral: about 1.5 mm into the glenoid
  ASSERT_TRUE(f.session().waitIdle(120000));
  ASSERT_GE(f.session().cutsCommitted(), 2u);
  f.session().moveReamer(advancedAlongAxis(f.session().reamer()->pose(), -14.0));
  ASSERT_TRUE(f.session().waitIdle(60000));
  w.action("depth_colouring")->trigger();
  w.action("view_en_face")->trigger();
  vtkCamera* cam = view->renderer()->GetActiveCamera();
  cam->Azimuth(-50);
  cam->Elevation(20);
  cam->OrthogonalizeViewUp();
  cam->SetParallelScale(38);
  view->render();
  const QImage shot = view->grabFramebuffer();
  ASSERT_EQ(shot.size(), QSize(640, 480) * view->devicePixelRatio());

  const QString baseline = QDir(REAMSIM_BASELINE_DIR).filePath("gui_reamed_glenoid_640x480.png");
  if (qEnvironmentVariableIsSet("REAMSIM_UPDATE_BASELINES")) {
    ASSERT_TRUE(shot.save(baseline));
    FAIL() << "baseline rewritten: " << baseline.toStdString() << " (unset REAMSIM_UPDATE_BASELINES)";
  }
  const QImage expected(baseline);
  ASSERT_FALSE(expected.isNull()) << "missing baseline " << baseline.toStdString();
  ASSERT_EQ(expected.size(), shot.size());
  const ImageDiff d = compare(shot, expected);
  const QString actual = QDir(REAMSIM_TEST_OUTPUT_DIR).filePath("gui_reamed_glenoid_actual.png");
  if (d.meanAbs > 2.0 || d.differingShare > 0.01) shot.save(actual);
  EXPECT_LT(d.meanAbs, 2.0) << "actual image written to " << actual.toStdString();
  EXPECT_LT(d.differingShare, 0.01) << "actual image written to " << actual.toStdString();
  // The picture must show the cut: depth colours (saturated, unlike bone and background) are present.
  int coloured = 0;
  for (int y = 0; y < shot.height(); y += 2)
    for (int x = 0; x < shot.width(); x += 2) coloured += QColor(shot.pixel(x, y)).saturation() > 150;
  EXPECT_GT(coloured, 200);
}

}  // namespace
}  // namespace reamsim::ui::test
