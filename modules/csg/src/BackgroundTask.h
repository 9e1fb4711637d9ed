#pragma once
// Work the cutting engine hands to the machine's second core, run on threads kept for the process rather than
// one started per task: std::async starts and joins a thread for ~50 µs here, and a cut hands over up to five
// tasks. A task is never queued behind another (with no idle thread a new one is started), so tasks that
// wait for each other cannot deadlock; and like std::async's future, a BackgroundTask waits for its work
// when destroyed, so work that reads the caller's stack never outlives it (an exception on the way out): a
// job that no thread has started by then is run by the caller (below), never later on a pool thread.
#include <atomic>
#include <functional>
#include <future>
#include <memory>
#include <type_traits>
#include <utility>

namespace reamsim::csg {

// Runs `job` on an idle pool thread, or on a new thread when none is idle.
void startInBackground(std::function<void()> job);

// The task is claimed once, by a pool thread when it starts or by the caller when it asks for the result first:
// a caller that needs the result before a pool thread has taken the job (the second core is busy with
// another process, or the thread is still waking) runs it itself instead of waiting for a core.
template <class R>
class BackgroundTask {
 public:
  BackgroundTask() = default;
  template <class F>
  explicit BackgroundTask(F&& work) : shared_(std::make_shared<Shared>(std::forward<F>(work))) {
    future_ = shared_->task.get_future();
    startInBackground([s = shared_] { s->runIfUnclaimed(); });
  }
  BackgroundTask(BackgroundTask&&) noexcept = default;
  BackgroundTask& operator=(BackgroundTask&& other) noexcept {
    wait();
    shared_ = std::move(other.shared_);
    future_ = std::move(other.future_);
    return *this;
  }
  ~BackgroundTask() { wait(); }
  bool valid() const { return future_.valid(); }
  void wait() const {
    if (!future_.valid()) return;
    shared_->runIfUnclaimed();
    future_.wait();
  }
  R get() {  // the work's result, or its exception
    shared_->runIfUnclaimed();
    return future_.get();
  }

 private:
  struct Shared {
    template <class F>
    explicit Shared(F&& work) : task(std::forward<F>(work)) {}
    void runIfUnclaimed() {
      bool expected = false;
      if (claimed.compare_exchange_strong(expected, true, std::memory_order_acq_rel)) task();
    }
    std::packaged_task<R()> task;
    std::atomic<bool> claimed{false};
  };
  // The pool's copy of the job holds `shared_` too: a job the caller ran itself is only dropped there.
  std::shared_ptr<Shared> shared_;
  std::future<R> future_;
};

template <class F>
BackgroundTask<std::invoke_result_t<std::decay_t<F>&>> inBackground(F&& work) {
  return BackgroundTask<std::invoke_result_t<std::decay_t<F>&>>(std::forward<F>(work));
}

}  // namespace reamsim::csg
