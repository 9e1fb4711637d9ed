#include "BackgroundTask.h"

#include <array>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace reamsim::csg {
namespace {

// A few threads started on first use and kept until the process ends. Three, not one: a cut runs at most two
// tasks at once, and a thread that has just finished a job may not have marked itself idle yet.
class Pool {
 public:
  bool tryStart(std::function<void()>& job) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (Worker& w : workers_) {
      if (w.busy) continue;
      if (!w.thread.joinable()) w.thread = std::thread([this, &w] { loop(w); });
      w.job = std::move(job);
      w.busy = true;
      w.wake.notify_one();
      return true;
    }
    return false;
  }
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    for (Worker& w : workers_) {
      w.wake.notify_one();
      if (w.thread.joinable()) w.thread.join();
    }
  }

 private:
  struct Worker {
    std::thread thread;
    std::condition_variable wake;
    std::function<void()> job;
    bool busy = false;
  };
  void loop(Worker& w) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      w.wake.wait(lock, [&] { return stopping_ || w.job; });
      if (!w.job) return;  // stopping, nothing left to run
      std::function<void()> job = std::move(w.job);
      w.job = nullptr;
      lock.unlock();
      job();  // a packaged_task: it keeps its own exceptions
      job = nullptr;
      lock.lock();
      w.busy = false;
    }
  }
  std::mutex mutex_;
  std::array<Worker, 3> workers_;
  bool stopping_ = false;
};

Pool& pool() {
  static Pool p;
  return p;
}

}  // namespace

void startInBackground(std::function<void()> job) {
  if (pool().tryStart(job)) return;
  std::thread(std::move(job)).detach();  // every pool thread busy: a thread of its own
}

}  // namespace reamsim::csg
