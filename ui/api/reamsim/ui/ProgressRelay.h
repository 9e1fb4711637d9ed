#pragma once
// A progress callback (reamsim/mesh/RepairProgress.h) for work on a worker thread: forwards (fraction, stage)
// to `apply` on the receiver's thread, at most every 0.5 % or on a new stage (the UI is not flooded), and
// asks the work to stop when `cancel` is set. Safe if the receiver is gone by the time an update arrives
// (it is then dropped). Used by the main window's import and the CT import dialog.
#include <QMetaObject>
#include <QObject>
#include <QPointer>
#include <QString>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "reamsim/mesh/RepairProgress.h"

namespace reamsim::ui {

inline ProgressCallback progressRelay(QObject* receiver, std::function<void(double, QString)> apply,
                                      std::shared_ptr<std::atomic<bool>> cancel) {
  struct State {
    std::mutex mutex;
    int lastPermille = -1000;
    std::string lastStage;
  };
  auto state = std::make_shared<State>();
  QPointer<QObject> target(receiver);
  return [state, target, apply = std::move(apply), cancel](double fraction, const std::string& stage) {
    const int permille = int(std::lround(fraction * 1000));
    bool post = false;
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      if (stage != state->lastStage || std::abs(permille - state->lastPermille) >= 5) {
        state->lastStage = stage;
        state->lastPermille = permille;
        post = true;
      }
    }
    // A queued call to a deleted receiver is dropped by Qt; `target` only avoids posting to one.
    if (post && target)
      QMetaObject::invokeMethod(
          target.data(), [apply, fraction, s = QString::fromStdString(stage)] { apply(fraction, s); },
          Qt::QueuedConnection);
    return !cancel->load();
  };
}

}  // namespace reamsim::ui
