#pragma once
// Work the cutting engine hands to the machine's second core, run on threads kept for the process rather than
// one started per task: std::async starts and joins a thread for ~50 µs here, and a cut hands over up to five
// tasks. A task is never queued behind another (with no idle thread a new one is started), so tasks that
// wait for each other cannot deadlock; and like std::async's future, a BackgroundTask waits for its work
// when destroyed, so work that reads the caller's stack never outlives it (an exception on the way out).
#include <functional>
#include <future>
#include <memory>
#include <type_traits>
#include <utility>

namespace reamsim::csg {

// Runs `job` on an idle pool thread, or on a new thread when none is idle.
void startInBackground(std::function<void()> job);

template <class R>
class BackgroundTask {
 public:
  BackgroundTask() = default;
  template <class F>
  explicit BackgroundTask(F&& work) {
    auto task = std::make_shared<std::packaged_task<R()>>(std::forward<F>(work));
    future_ = task->get_future();
    startInBackground([task] { (*task)(); });
  }
  BackgroundTask(BackgroundTask&&) noexcept = default;
  BackgroundTask& operator=(BackgroundTask&& other) noexcept {
    wait();
    future_ = std::move(other.future_);
    return *this;
  }
  ~BackgroundTask() { wait(); }
  bool valid() const { return future_.valid(); }
  void wait() const {
    if (future_.valid()) future_.wait();
  }
  R get() { return future_.get(); }  // the work's result, or its exception

 private:
  std::future<R> future_;
};

template <class F>
BackgroundTask<std::invoke_result_t<std::decay_t<F>&>> inBackground(F&& work) {
  return BackgroundTask<std::invoke_result_t<std::decay_t<F>&>>(std::forward<F>(work));
}

}  // namespace reamsim::csg
