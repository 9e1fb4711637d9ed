#pragma once
// The non-interactive runs of the `reamsim` executable, on the real window:
//  - demo: the default case, the default plan run through the user's "Ream to depth" path, a screenshot;
//  - key-to-frame latency benchmark: key events through Qt's input path, timed to the presented frame.
#include <QString>

namespace reamsim::ui {

class MainWindow;

bool waitExposed(MainWindow& window, int timeoutMs);

// Returns the process exit code; prints a one-line summary (or an error) to stderr.
int runDemo(MainWindow& window, const QString& screenshotPath);

struct LatencyOptions {
  QString bone = "default";  // "default" or a mesh path (loaded without repair: display + collision)
  int presses = 40;
  bool inContact = false;    // start 0.5 mm past the first contact (glenoid for the default bone, else from
                             // above the bone): every press then cuts on the worker
  bool json = false;
};
int runLatencyBench(MainWindow& window, const LatencyOptions& options);

}  // namespace reamsim::ui
