// reamsim: the desktop application.
//   reamsim [MESH]                              open a bone (or the default case)
//   reamsim --demo [--screenshot FILE.png]      default case + default plan through the GUI, screenshot, exit
//   reamsim --bench-latency [--bone default|MESH] [--presses N] [--in-contact] [--json]
//                                              median key-press-to-frame latency on the real window
//   --plugin-dir DIR                            load plugins from DIR (default: next to the executable)
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QVTKOpenGLNativeWidget.h>
#include <cstdio>

#include "AppModes.h"
#include "MainWindow.h"
#include "NumericLocale.h"
#include "PluginHost.h"

int main(int argc, char** argv) {
  // Must precede QApplication: VTK needs a core-profile context from every QOpenGLWidget.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  reamsim::ui::useCNumberFormats();  // numbers in files never follow the user's locale
  QCoreApplication::setOrganizationName("ReamSim");
  QCoreApplication::setApplicationName("reamsim");

  QCommandLineParser parser;
  parser.setApplicationDescription("ReamSim: glenoid reaming simulator");
  parser.addHelpOption();
  parser.addPositionalArgument("mesh", "Bone mesh to open (STL, OBJ, PLY, OFF, VTP)", "[mesh]");
  const QCommandLineOption pluginDir("plugin-dir", "Load plugins from DIR.", "DIR");
  const QCommandLineOption demo("demo", "Run the default plan on the default case through the GUI, then exit.");
  const QCommandLineOption screenshot("screenshot", "With --demo: write a screenshot of the window.", "FILE");
  const QCommandLineOption bench("bench-latency", "Measure key-press-to-frame latency, then exit.");
  const QCommandLineOption bone("bone", "With --bench-latency: default or a mesh file.", "BONE", "default");
  const QCommandLineOption presses("presses", "With --bench-latency: number of key presses.", "N", "40");
  const QCommandLineOption inContact("in-contact",
                                     "With --bench-latency: start 0.5 mm into the bone (every press cuts).");
  const QCommandLineOption json("json", "With --bench-latency: print one JSON object.");
  parser.addOptions({pluginDir, demo, screenshot, bench, bone, presses, inContact, json});
  parser.process(app);

  reamsim::ui::PluginHost plugins;
  plugins.loadFrom(parser.isSet(pluginDir) ? parser.value(pluginDir) : reamsim::ui::PluginHost::defaultPluginDir());
  const bool scripted = parser.isSet(demo) || parser.isSet(bench);
  reamsim::ui::MainWindow window(plugins, !scripted);

  if (parser.isSet(demo)) return reamsim::ui::runDemo(window, parser.value(screenshot));
  if (parser.isSet(bench)) {
    reamsim::ui::LatencyOptions o;
    o.bone = parser.value(bone);
    bool ok = false;
    o.presses = parser.value(presses).toInt(&ok);
    if (!ok || o.presses < 1) {
      std::fprintf(stderr, "reamsim: --presses must be a positive integer, not '%s'\n", qPrintable(parser.value(presses)));
      return 2;
    }
    o.inContact = parser.isSet(inContact);
    o.json = parser.isSet(json);
    return reamsim::ui::runLatencyBench(window, o);
  }
  window.show();
  if (!parser.positionalArguments().isEmpty()) {
    window.openFile(parser.positionalArguments().front());
  } else {
    window.loadDefaultCase();
  }
  return app.exec();
}
