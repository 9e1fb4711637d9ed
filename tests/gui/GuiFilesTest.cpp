// Bones in and out of the window: import errors in a dialog with the importer's message (never a crash),
// a valid mesh replaces the bone, save in another format, recent files, drag and drop, CSV export.
#include <QCoreApplication>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QFile>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QUrl>
#include <QtTest/QTest>

#include "GuiEnvironment.h"
#include "reamsim/mesh/MeshIO.h"

namespace reamsim::ui::test {
namespace {

const QString kData = REAMSIM_TEST_DATA_DIR;

TEST(GuiFiles, MalformedFileShowsTheImporterMessageAndKeepsTheBone) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  const QString path = kData + "/malformed/stl_ascii_bad_number.stl";
  w.openFile(path);
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains("stl_ascii_bad_number.stl")) << w.lastError().toStdString();
  EXPECT_TRUE(w.lastError().contains("cannot parse vertex x from '1.0abc'")) << w.lastError().toStdString();
  auto* box = w.findChild<QMessageBox*>("ErrorDialog");
  ASSERT_NE(box, nullptr);
  EXPECT_TRUE(box->isVisible());
  EXPECT_TRUE(box->text().contains("1.0abc"));
  box->close();
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);
  EXPECT_TRUE(w.recentFiles().isEmpty());
}

TEST(GuiFiles, CancelledImportGivesTheWindowBackAndDiscardsTheResult) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  const std::uint64_t revision = f.session().bone()->currentRevision();
  // The bundled OpenSim scapula with repair: a volumetric remesh, seconds of work on the worker.
  w.openFile(QString(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp", true);
  ASSERT_TRUE(w.importRunning());
  auto* cancel = w.findChild<QPushButton*>("CancelImport");
  ASSERT_NE(cancel, nullptr);
  EXPECT_TRUE(cancel->isVisible());
  // Into the repair (the file is read in a moment) before Cancel.
  bool repairing = false;
  const QMetaObject::Connection heard = QObject::connect(
      w.statusBar(), &QStatusBar::messageChanged, [&](const QString& m) { repairing |= m.contains("remesh"); });
  ASSERT_TRUE(QTest::qWaitFor([&] { return repairing || !w.importRunning(); }, 300000));
  QObject::disconnect(heard);
  ASSERT_TRUE(repairing);
  QTest::mouseClick(cancel, Qt::LeftButton);
  EXPECT_FALSE(cancel->isVisible());
  w.waitImport();
  // The worker stopped at one of the repair's checks rather than finishing the remesh.
  EXPECT_FALSE(w.lastImportStoppedAt().isEmpty());
  EXPECT_NE(w.lastImportStoppedAt(), "reading");
  EXPECT_NE(w.lastImportStoppedAt(), "parsing");
  EXPECT_EQ(f.session().bone()->currentRevision(), revision);  // the result was discarded
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_TRUE(w.recentFiles().isEmpty());
  // The next import works as usual.
  w.openFile(kData + "/malformed/stl_ascii_bad_number.stl");
  w.waitImport();
  EXPECT_TRUE(w.lastError().contains("stl_ascii_bad_number.stl"));
}

// A large text file: the status bar follows its reading and parsing, and Cancel stops the worker inside them
// (ReadOptions::progress) instead of after the whole file is read.
TEST(GuiFiles, CancelStopsTheReadingOfALargeFile) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  TriangleMesh large;  // 400,000 triangles of OBJ text, ~15 MB: a few tenths of a second to parse
  for (int k = 0; k < 50000; ++k) {
    const auto base = static_cast<std::uint32_t>(large.vertices.size());
    for (Vec3 p : {Vec3{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}})
      large.vertices.push_back(p + Vec3{3.0 * (k % 400), 3.0 * (k / 400), 0});
    for (Triangle t : std::initializer_list<Triangle>{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}})
      large.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  QTemporaryDir dir;
  const QString path = dir.filePath("large.obj");
  writeMesh(large, path.toStdString());
  const std::uint64_t revision = f.session().bone()->currentRevision();

  QStringList stages;
  const QMetaObject::Connection heard = QObject::connect(w.statusBar(), &QStatusBar::messageChanged, [&](const QString& m) {
    for (const char* stage : {": reading", ": parsing", ": validation"})
      if (m.endsWith(stage) && (stages.isEmpty() || stages.back() != stage)) stages << stage;
  });
  w.openFile(path, false);
  QElapsedTimer guard;  // a deadline for a hung worker, not a measurement
  guard.start();
  while (w.importRunning() && guard.elapsed() < 300000) QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  w.waitImport();
  QObject::disconnect(heard);
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), large.triangles.size());
  EXPECT_TRUE(stages.contains(": parsing")) << stages.join(' ').toStdString();
  EXPECT_EQ(stages.indexOf(": parsing") < stages.indexOf(": validation") || !stages.contains(": validation"), true);

  const std::uint64_t opened = f.session().bone()->currentRevision();
  ASSERT_NE(opened, revision);
  w.openFile(path, false);
  ASSERT_TRUE(w.importRunning());
  QTest::mouseClick(w.findChild<QPushButton*>("CancelImport"), Qt::LeftButton);
  w.waitImport();
  // Stopped while the file was read or parsed, not at the validation after it.
  EXPECT_TRUE(w.lastImportStoppedAt() == "reading" || w.lastImportStoppedAt() == "parsing")
      << w.lastImportStoppedAt().toStdString();
  EXPECT_EQ(f.session().bone()->currentRevision(), opened);
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
}

TEST(GuiFiles, ImportShowsTheRepairsProgress) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f;
  MainWindow& w = *f.window;
  // The OpenSim scapula with repair: the remesh reports its stages and fractions while the worker runs.
  w.openFile(QString(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_opensim.vtp", true);
  auto* bar = w.findChild<QProgressBar*>("ImportProgress");
  ASSERT_NE(bar, nullptr);
  // Every message and value the window shows, as it shows them (not sampled: a fast machine may pass a stage
  // between two polls).
  bool sawRemesh = false, sawFraction = false;
  QObject::connect(w.statusBar(), &QStatusBar::messageChanged,
                   [&](const QString& m) { sawRemesh |= m.contains("remesh: inside and outside near the surface"); });
  QObject::connect(bar, &QProgressBar::valueChanged, [&](int v) { sawFraction |= bar->maximum() == 1000 && v > 0; });
  QElapsedTimer guard;  // a deadline for a hung worker, not a measurement
  guard.start();
  while (w.importRunning() && guard.elapsed() < 300000) QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  w.waitImport();
  EXPECT_TRUE(sawRemesh);
  EXPECT_TRUE(sawFraction);
  EXPECT_TRUE(w.lastImportStoppedAt().isEmpty());
  EXPECT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_TRUE(f.session().canCut()) << f.session().cuttingStatus().toStdString();
}

TEST(GuiFiles, WithoutRepairAClosedOutwardBoneIsCuttableAnOpenOneIsNot) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f(REAMSIM_GUI_PLUGIN_DIR, false);
  MainWindow& w = *f.window;
  w.openFile(kData + "/good/cube_quads_comments.off", false);  // closed and outward as read
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_TRUE(f.session().canCut()) << f.session().cuttingStatus().toStdString();
  EXPECT_NE(f.session().bone()->importReport().find("closed and outward"), std::string::npos)
      << f.session().bone()->importReport();
  w.openFile(kData + "/good/strip_and_quad.vtp", false);  // an open strip
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_FALSE(f.session().canCut());
  EXPECT_NE(f.session().bone()->importReport().find("cutting disabled"), std::string::npos)
      << f.session().bone()->importReport();
}

TEST(GuiFiles, OpenSaveRecentDropAndCsvExport) {
  REAMSIM_REQUIRE_DISPLAY();
  GuiFixture f(REAMSIM_GUI_PLUGIN_DIR, false);
  MainWindow& w = *f.window;
  const QString cube = kData + "/good/cube_quads_comments.off";
  w.openFile(cube);
  w.waitImport();
  ASSERT_TRUE(w.lastError().isEmpty()) << w.lastError().toStdString();
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), 12u);
  EXPECT_TRUE(f.session().canCut()) << f.session().cuttingStatus().toStdString();
  ASSERT_EQ(w.recentFiles().size(), 1);
  EXPECT_TRUE(w.recentFiles().front().endsWith("cube_quads_comments.off"));
  EXPECT_TRUE(w.windowTitle().contains("cube_quads_comments.off"));

  QTemporaryDir out;
  const QString saved = out.filePath("bone.stl");
  w.saveBoneAs(saved);
  ASSERT_TRUE(QFile::exists(saved)) << w.lastError().toStdString();
  EXPECT_EQ(readMesh(saved.toStdString()).mesh.triangles.size(), 12u);
  w.saveBoneAs(out.filePath("bone.unknownformat"));  // refused with the writer's message
  EXPECT_TRUE(w.lastError().contains("bone.unknownformat")) << w.lastError().toStdString();

  // Drag and drop a file onto the window: it is opened like File → Open.
  QMimeData mime;
  mime.setUrls({QUrl::fromLocalFile(kData + "/good/tetra_le_vertex_index.ply")});
  QDragEnterEvent enter(QPoint(50, 50), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &enter);
  EXPECT_TRUE(enter.isAccepted());
  QDropEvent drop(QPointF(50, 50), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &drop);
  w.waitImport();
  EXPECT_EQ(f.session().bone()->current().liveTriangleCount(), 4u);
  EXPECT_EQ(w.recentFiles().size(), 2);

  // CSV export of the (empty) log through the panel: header only.
  auto* panel = w.findChild<QDockWidget*>("LogPanel");
  ASSERT_NE(panel, nullptr);
  QString error;
  ASSERT_TRUE(QMetaObject::invokeMethod(panel, "exportCsv", Q_RETURN_ARG(QString, error),
                                        Q_ARG(QString, out.filePath("log.csv")), Q_ARG(bool, false)));
  EXPECT_TRUE(error.isEmpty()) << error.toStdString();
  QFile csv(out.filePath("log.csv"));
  ASSERT_TRUE(csv.open(QIODevice::ReadOnly));
  EXPECT_EQ(csv.readAll().count('\n'), 1);
}

}  // namespace
}  // namespace reamsim::ui::test
