// The plugin host: a missing plugin leaves the application running, reduced; a broken file is listed with
// the loader's reason; Help → Plugins shows all of it.
#include <QDialog>
#include <QDir>
#include <QFile>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest/QTest>

#include <algorithm>
#include <string>
#include <vector>

#include "GuiEnvironment.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/RepairProgress.h"

namespace reamsim::ui::test {
namespace {

const PluginRecord* find(const PluginHost& host, const QString& name) {
  for (const PluginRecord& r : host.records())
    if (r.name == name) return &r;
  return nullptr;
}

TEST(GuiPlugins, AllPluginsLoadFromTheBuildTree) {
  REAMSIM_REQUIRE_DISPLAY();
  PluginHost host;
  host.loadFrom(REAMSIM_GUI_PLUGIN_DIR);
  for (const QString& name : PluginHost::expectedPlugins()) {
    const PluginRecord* r = find(host, name);
    ASSERT_NE(r, nullptr) << name.toStdString();
    EXPECT_TRUE(r->loaded) << name.toStdString() << ": " << r->detail.toStdString();
  }
  EXPECT_NE(host.meshImport(), nullptr);
  EXPECT_NE(host.collision(), nullptr);
  EXPECT_NE(host.csg(), nullptr);
  EXPECT_EQ(host.panels().size(), 2u);  // the log and the planning docks
}

// Opening without repair still validates the mesh (a self-intersection count, seconds on a large scan):
// it reports its progress and stops when asked, as the repair does.
TEST(GuiPlugins, MeshImportWithoutRepairReportsAndStopsItsValidation) {
  REAMSIM_REQUIRE_DISPLAY();
  PluginHost host;
  host.loadFrom(REAMSIM_GUI_PLUGIN_DIR);
  const MeshImportInterface* importer = host.meshImport();
  ASSERT_NE(importer, nullptr);
  const std::string path = std::string(REAMSIM_RESOURCE_DIR) + "/bones/scapula_R_repaired.ply";
  std::vector<std::string> stages;
  const RepairProgress watch = [&](double, const std::string& stage) {
    stages.push_back(stage);
    return true;
  };
  const ImportedBone bone = importer->importBone(path, false, watch);
  EXPECT_TRUE(bone.cuttable) << bone.report;
  ASSERT_FALSE(stages.empty());
  EXPECT_EQ(stages.front(), "reading");  // the file's bytes, then their parse (ReadOptions::progress)
  EXPECT_NE(std::find(stages.begin(), stages.end(), "validation"), stages.end());
  const RepairProgress stop = [](double, const std::string&) { return false; };
  EXPECT_THROW(importer->importBone(path, false, stop), ReadCancelled);
  // Stopped at the validation's first check: the read let go on.
  const RepairProgress stopValidating = [](double, const std::string& stage) { return stage != "validation"; };
  EXPECT_THROW(importer->importBone(path, false, stopValidating), RepairCancelled);
}

TEST(GuiPlugins, StartsReducedWithoutCsgAndListsWhatFailed) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir dir;
  for (const char* name : {"meshimport", "collision", "logpanel"}) {
    const QString file = QString("libreamsim_") + name + ".so";
    ASSERT_TRUE(QFile::copy(QDir(REAMSIM_GUI_PLUGIN_DIR).filePath(file), dir.filePath(file)));
  }
  QFile broken(dir.filePath("libreamsim_broken.so"));
  ASSERT_TRUE(broken.open(QIODevice::WriteOnly));
  broken.write("this is not a shared library");
  broken.close();

  GuiFixture f(dir.path());
  const PluginHost& host = *f.plugins;
  EXPECT_EQ(host.csg(), nullptr);
  const PluginRecord* csg = find(host, "csg");
  ASSERT_NE(csg, nullptr);
  EXPECT_FALSE(csg->loaded);
  EXPECT_TRUE(csg->detail.contains("not found")) << csg->detail.toStdString();
  const PluginRecord* bad = find(host, "libreamsim_broken");
  ASSERT_NE(bad, nullptr);
  EXPECT_FALSE(bad->loaded);
  EXPECT_FALSE(bad->detail.isEmpty());

  // Reduced: collision alerts, no cutting; feeding into the glenoid leaves the bone as it was, and the exact
  // collision engine reports the contact it cannot cut.
  MainWindow& w = *f.window;
  EXPECT_FALSE(f.session().canCut());
  EXPECT_TRUE(f.session().canCollide());
  const double volume = f.session().bone()->current().volume();
  w.setSteps(0.5, 2.0, 2.5);
  QTest::keyClick(w.windowHandle(), Qt::Key_PageDown);
  ASSERT_TRUE(f.session().waitIdle(60000));
  EXPECT_EQ(f.session().bone()->current().volume(), volume);
  EXPECT_TRUE(f.session().alerts()->has(AlertKind::BoundsOverlap));
  EXPECT_TRUE(f.session().alerts()->has(AlertKind::Contact));
  EXPECT_EQ(w.statusAlertText(), "CONTACT");
  EXPECT_EQ(f.session().log()->size(), 0u);

  w.showPluginsDialog();
  auto* dialog = w.findChild<QDialog*>("PluginsDialog");
  ASSERT_NE(dialog, nullptr);
  EXPECT_TRUE(dialog->isVisible());
  auto* table = dialog->findChild<QTableWidget*>("PluginsTable");
  ASSERT_NE(table, nullptr);
  EXPECT_EQ(table->rowCount(), static_cast<int>(host.records().size()));
  QStringList failed;
  for (int i = 0; i < table->rowCount(); ++i)
    if (table->item(i, 1)->text() == "failed") failed << table->item(i, 0)->text();
  EXPECT_TRUE(failed.contains("csg"));
  EXPECT_TRUE(failed.contains("libreamsim_broken"));
  dialog->close();
}

TEST(GuiPlugins, RunsWithNoPluginsAtAll) {
  REAMSIM_REQUIRE_DISPLAY();
  QTemporaryDir empty;
  GuiFixture f(empty.path());
  EXPECT_EQ(f.plugins->records().size(), static_cast<std::size_t>(PluginHost::expectedPlugins().size()));
  EXPECT_FALSE(f.session().canCollide());
  const Pose p0 = f.session().reamer()->pose();
  QTest::keyClick(f.window->windowHandle(), Qt::Key_Right);  // the reamer still moves
  EXPECT_GT(f.session().reamer()->pose().tip.x, p0.tip.x);
  f.window->openFile("/nonexistent.stl");  // no importer: a clear message, no crash
  EXPECT_TRUE(f.window->lastError().contains("no mesh import plugin")) << f.window->lastError().toStdString();
}

}  // namespace
}  // namespace reamsim::ui::test
