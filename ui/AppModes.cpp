#include "AppModes.h"

#include <vtkCamera.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderer.h>

#include <QAction>
#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QGuiApplication>
#include <QPixmap>
#include <QTimer>
#include <QWindow>
#include <algorithm>
#include <cstdio>
#include <string>
#include <QtTest/QTest>
#include <vector>

#include "CachedBoneLayer.h"
#include "MainWindow.h"
#include "PluginHost.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/DefaultCase.h"

namespace reamsim::ui {
namespace {

void pump(int ms) {
  QEventLoop loop;
  QTimer::singleShot(ms, &loop, &QEventLoop::quit);
  loop.exec();
}

// Waits for the view's next presented frame (QOpenGLWidget::frameSwapped); false on timeout.
bool waitFrame(BoneView* view, int timeoutMs) {
  QEventLoop loop;
  bool swapped = false;
  auto c = QObject::connect(view, &QOpenGLWidget::frameSwapped, &loop, [&] {
    swapped = true;
    loop.quit();
  });
  QTimer::singleShot(timeoutMs, &loop, &QEventLoop::quit);
  loop.exec();
  QObject::disconnect(c);
  return swapped;
}

QString glRenderer(BoneView* view) {
  auto* w = vtkOpenGLRenderWindow::SafeDownCast(view->renderWindow());
  if (!w) return "unknown";
  const QString caps = QString::fromStdString(w->ReportCapabilities() ? w->ReportCapabilities() : "");
  for (const QString& line : caps.split('\n'))
    if (line.contains("OpenGL renderer string")) return line.section(':', 1).trimmed();
  return "unknown";
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

}  // namespace

bool waitExposed(MainWindow& window, int timeoutMs) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < timeoutMs) {
    if (window.windowHandle() && window.windowHandle()->isExposed() && window.view()->isValid()) break;
    pump(20);
  }
  if (!window.windowHandle() || !window.windowHandle()->isExposed()) return false;
  // Keys go to the active window. Without a window manager (xvfb) activation may never come: force it.
  window.activateWindow();
  for (int i = 0; i < 25 && !window.isActiveWindow(); ++i) pump(20);
  if (!window.isActiveWindow()) QApplication::setActiveWindow(&window);
  return true;
}

int runDemo(MainWindow& window, const QString& screenshotPath) {
  window.resize(1280, 800);
  window.show();
  if (!waitExposed(window, 10000)) {
    std::fprintf(stderr, "reamsim --demo: the window was not shown (no display?)\n");
    return 2;
  }
  if (!window.loadDefaultCase()) {
    std::fprintf(stderr, "reamsim --demo: %s\n", qPrintable(window.lastError()));
    return 1;
  }
  ReamSession& session = window.session();
  if (!session.canCut()) {
    std::fprintf(stderr, "reamsim --demo: cutting is unavailable: %s\n", qPrintable(session.cuttingStatus()));
    return 1;
  }
  session.waitIdle(60000);
  // The default plan is a feed along the start pose's axis: run it as a user would, "Feed along the axis by".
  const ReamPlan plan = loadPlan(defaultPlanPath());
  window.setSteps(0.5, 2.0, plan.feed ? plan.feed->stepMm : 0.2);
  const double depth = plan.feed ? plan.feed->stepMm * plan.feed->count : 5.0;
  QElapsedTimer timer;
  timer.start();
  window.feedBy(depth);
  if (!session.waitIdle(600000)) {
    std::fprintf(stderr, "reamsim --demo: the plan did not finish in 10 minutes\n");
    return 1;
  }
  const double seconds = timer.elapsed() / 1000.0;
  // Back the reamer off along its axis so the reamed glenoid shows, then a three-quarter view onto it.
  session.moveReamer(advancedAlongAxis(session.reamer()->pose(), -14.0));
  session.waitIdle(60000);
  window.action("depth_colouring")->trigger();
  window.view()->setStandardView(BoneView::StandardView::EnFace);
  vtkCamera* cam = window.view()->renderer()->GetActiveCamera();
  cam->Azimuth(-50);
  cam->Elevation(20);
  cam->OrthogonalizeViewUp();
  cam->SetParallelScale(38);
  window.view()->render();
  pump(300);
  const LogNode* log = session.log();
  std::fprintf(stderr, "reamsim --demo: %zu cuts, %.1f mm3 removed, %zu faces, %.1f s\n", session.cutsCommitted(),
               log->cumulativeMm3(), session.bone()->current().liveTriangleCount(), seconds);
  if (session.cutsCommitted() == 0) {
    std::fprintf(stderr, "reamsim --demo: the plan made no cut\n");
    return 1;
  }
  if (!screenshotPath.isEmpty()) {
    const QPixmap shot = window.grab();
    if (shot.isNull() || !shot.save(screenshotPath)) {
      std::fprintf(stderr, "reamsim --demo: cannot write the screenshot %s\n", qPrintable(screenshotPath));
      return 1;
    }
    std::fprintf(stderr, "reamsim --demo: screenshot %s (%dx%d)\n", qPrintable(screenshotPath), shot.width(),
                 shot.height());
  }
  return 0;
}

int runLatencyBench(MainWindow& window, const LatencyOptions& o) {
  window.resize(1280, 800);
  window.show();
  window.activateWindow();
  if (!waitExposed(window, 10000)) {
    std::fprintf(stderr, "reamsim --bench-latency: the window was not shown (no display?)\n");
    return 2;
  }
  ReamSession& session = window.session();
  if (o.bone == "default") {
    if (!window.loadDefaultCase()) return 1;
  } else {
    window.openFile(o.bone, false);
    window.waitImport();
    if (session.bone()->current().empty()) {
      std::fprintf(stderr, "reamsim --bench-latency: %s\n", qPrintable(window.lastError()));
      return 1;
    }
  }
  session.waitIdle(60000);
  const Bounds b = session.bone()->current().bounds();
  // Beside the bone, outside its bounding box, pointing down at it: every move runs the collision query only.
  Pose start{{b.center().x, b.center().y, b.max.z + 30.0}, {0, 0, -1}, 0};
  if (o.inContact) {
    if (o.bone == "default" && session.plan() && !session.plan()->poses().empty()) start = session.plan()->poses().front();
    const auto approach = advanceToContactMm(session.bone()->current(), *session.reamer()->cuttingVolume(), start, 200,
                                             &session.reamer()->spec());
    if (!approach) {
      std::fprintf(stderr, "reamsim --bench-latency: the reamer meets no bone along its axis\n");
      return 1;
    }
    start = advancedAlongAxis(start, *approach + 0.5);
  }
  session.moveReamer(start);
  session.waitIdle(60000);
  window.view()->resetView();
  window.setSteps(0.5, 2.0, 0.2);
  pump(200);

  QWindow* handle = window.windowHandle();
  std::vector<double> ms, vtkMs;
  int missed = 0, unmoved = 0;
  const std::size_t reusedBefore = window.view()->boneCache().reusedFrames();
  const std::size_t drawnBefore = window.view()->boneCache().drawnFrames();
  const int warmup = 5;
  for (int i = 0; i < warmup + o.presses; ++i) {
    const Qt::Key key = i % 2 ? Qt::Key_Left : Qt::Key_Right;  // back and forth: the scene stays put
    const double xBefore = session.reamer()->pose().tip.x;
    QElapsedTimer t;
    t.start();
    // Through Qt's input path (shortcut override, shortcut map, the action), as QTest delivers keys.
    QTest::keyPress(handle, key);
    const bool ok = waitFrame(window.view(), 5000);
    const double elapsed = t.nsecsElapsed() / 1e6;
    QTest::keyRelease(handle, key);
    if (session.reamer()->pose().tip.x == xBefore) ++unmoved;
    if (!ok) ++missed;
    if (i >= warmup && ok) {
      ms.push_back(elapsed);
      vtkMs.push_back(window.view()->lastRenderMs());
    }
    session.waitIdle(60000);  // one press at a time: the worker's step is not part of the next press
    pump(30);
  }
  if (unmoved > 0)
    std::fprintf(stderr, "reamsim --bench-latency: %d key presses did not move the reamer (window not active?)\n", unmoved);
  const double median = percentile(ms, 0.5);
  const QString renderer = glRenderer(window.view());
  const char* target = session.bone()->current().liveTriangleCount() >= 100000 ? "<= 33 ms at 400k faces" : "";
  const std::string pose = o.inContact ? "0.5 mm into the bone (collision + a cut on the worker per press)"
                                       : "outside bounding box (collision only)";
  if (o.json) {
    std::printf(
        "{\"bench\": \"key_to_frame\", \"bone\": \"%s\", \"faces\": %zu, \"presses\": %zu, \"missed_frames\": %d, "
        "\"median_ms\": %.2f, \"p90_ms\": %.2f, \"min_ms\": %.2f, \"max_ms\": %.2f, \"window\": \"%dx%d\", "
        "\"view\": \"%dx%d\", \"pose\": \"%s\", \"cuts\": %zu, \"renderer\": \"%s\", \"target\": \"%s\", "
        "\"vtk_render_median_ms\": %.2f, \"bone_layer_reused_frames\": %zu, \"bone_layer_drawn_frames\": %zu, "
        "\"bone_cache\": \"%s\"}\n",
        qPrintable(o.bone), session.bone()->current().liveTriangleCount(), ms.size(), missed, median,
        percentile(ms, 0.9), percentile(ms, 0.0), percentile(ms, 1.0), window.width(), window.height(),
        window.view()->width(), window.view()->height(), pose.c_str(), session.cutsCommitted(), qPrintable(renderer),
        target, percentile(vtkMs, 0.5), window.view()->boneCache().reusedFrames() - reusedBefore,
        window.view()->boneCache().drawnFrames() - drawnBefore,
        window.view()->boneCache().enabled() ? "on" : window.view()->boneCache().disabledReason().c_str());
  } else {
    std::printf("key-to-frame latency, %s (%zu faces, reamer %s): median %.2f ms, p90 %.2f ms over %zu presses; %s\n",
                qPrintable(o.bone), session.bone()->current().liveTriangleCount(), pose.c_str(), median,
                percentile(ms, 0.9), ms.size(), qPrintable(renderer));
  }
  std::fflush(stdout);
  return missed > 0 || unmoved > 0 ? 1 : 0;
}

}  // namespace reamsim::ui
