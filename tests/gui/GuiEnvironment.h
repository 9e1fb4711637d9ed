#pragma once
// One QApplication for all GUI tests (xcb: Qt's offscreen platform renders VTK views as 0x0), settings
// in a temporary folder, and helpers that build a main window on the real plugins.
#include <gtest/gtest.h>

#include <QString>
#include <memory>

#include "MainWindow.h"
#include "PluginHost.h"

namespace reamsim::ui::test {

bool haveDisplay();  // false: the GUI tests skip (run them under `xvfb-run -a`)

struct GuiFixture {
  std::unique_ptr<PluginHost> plugins;
  std::unique_ptr<MainWindow> window;

  // Shown, active, with the default case loaded and its first collision query done.
  explicit GuiFixture(const QString& pluginDir = REAMSIM_GUI_PLUGIN_DIR, bool loadDefault = true);
  ~GuiFixture();
  ReamSession& session() { return window->session(); }
};

#define REAMSIM_REQUIRE_DISPLAY() \
  if (!::reamsim::ui::test::haveDisplay()) GTEST_SKIP() << "no X display: run the GUI tests under xvfb-run -a"

}  // namespace reamsim::ui::test
