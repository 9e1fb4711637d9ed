#include "BackgroundTask.h"

#include <array>
#include <atomic>
#include <chrono>
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
    Worker* idle = nullptr;
    for (Worker& w : workers_) {
      if (w.busy) continue;
      if (w.thread.joinable() && !w.sleeping) {  // awake (spinning): takes the job without a wake-up
        idle = &w;
        break;
      }
      if (!idle) idle = &w;
    }
    if (!idle) return false;
    Worker& w = *idle;
    if (!w.thread.joinable()) w.thread = std::thread([this, &w] { loop(w); });
    w.job = std::move(job);
    w.busy = true;
    w.hasJob.store(true, std::memory_order_release);
    if (w.sleeping) w.wake.notify_one();  // a spinning worker sees hasJob: no system call
    return true;
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
    bool sleeping = false;              // waiting on `wake` (guarded by mutex_, like job and busy)
    std::atomic<bool> hasJob{false};    // job is set: what a spinning worker watches without the lock
  };
  void loop(Worker& w) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      w.sleeping = true;
      w.wake.wait(lock, [&] { return stopping_ || w.job; });
      w.sleeping = false;
      if (!w.job) return;  // stopping, nothing left to run
      std::function<void()> job = std::move(w.job);
      w.job = nullptr;
      w.hasJob.store(false, std::memory_order_relaxed);
      lock.unlock();
      job();  // a packaged_task: it keeps its own exceptions
      job = nullptr;
      lock.lock();
      w.busy = false;
      lock.unlock();
      spinForNextJob(w);
      lock.lock();
    }
  }
  // A cut hands over its next task within a millisecond or two of the last one; a sleeping thread costs the
  // caller a futex wake and starts tens of µs later on a virtual machine. So one worker at a time waits
  // awake for a while (the other core is otherwise idle during a cut) before it sleeps.
  void spinForNextJob(Worker& w) {
    bool expected = false;
    if (!spinning_.compare_exchange_strong(expected, true, std::memory_order_acquire)) return;
    const auto until = std::chrono::steady_clock::now() + kSpinBeforeSleeping;
    while (!w.hasJob.load(std::memory_order_acquire) && !stopping_.load(std::memory_order_relaxed)) {
      for (int i = 0; i < 64; ++i) cpuRelax();
      if (std::chrono::steady_clock::now() > until) break;
      std::this_thread::yield();  // a thread that has work on this core (another process's) goes first
    }
    spinning_.store(false, std::memory_order_release);
  }
  static void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  static constexpr std::chrono::microseconds kSpinBeforeSleeping{2000};
  std::mutex mutex_;
  std::array<Worker, 3> workers_;
  std::atomic<bool> stopping_{false};  // set under mutex_; atomic for the spinner, which holds no lock
  std::atomic<bool> spinning_{false};      // one worker spins at a time: two would take the main thread's core
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
