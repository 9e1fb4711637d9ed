// The engine's second-core tasks (src/BackgroundTask.h): results and exceptions come back through get(); a
// handle waits for its work when destroyed (work may read the caller's stack); tasks that wait on each
// other all run at once, more of them than the pool keeps (none is queued behind another); and the pool's
// threads are reused, not started per task.
#include "BackgroundTask.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace reamsim::csg {
namespace {

TEST(BackgroundTask, GivesTheResultAndTheException) {
  auto value = inBackground([] { return 42; });
  EXPECT_EQ(value.get(), 42);
  auto failing = inBackground([]() -> int { throw std::runtime_error("from the worker"); });
  EXPECT_THROW(failing.get(), std::runtime_error);
}

TEST(BackgroundTask, DestroyingTheHandleWaitsForTheWork) {
  std::atomic<bool> done{false};
  {
    auto task = inBackground([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      done = true;
    });
  }
  EXPECT_TRUE(done.load());
}

TEST(BackgroundTask, TasksWaitingOnEachOtherAllRun) {
  // Six tasks that each wait until all six have started: with any of them queued behind another this would
  // never finish (the pool keeps three threads).
  constexpr int kTasks = 6;
  std::mutex m;
  std::condition_variable cv;
  int started = 0;
  std::vector<BackgroundTask<void>> tasks;
  for (int i = 0; i < kTasks; ++i)
    tasks.push_back(inBackground([&] {
      std::unique_lock<std::mutex> lock(m);
      ++started;
      cv.notify_all();
      const bool all = cv.wait_for(lock, std::chrono::seconds(10), [&] { return started == kTasks; });
      if (!all) throw std::runtime_error("not all tasks ran at once");
    }));
  for (auto& t : tasks) EXPECT_NO_THROW(t.get());
}

TEST(BackgroundTask, ReusesItsThreads) {
  // A thread-local count of the tasks each thread has run: a thread started per task would always count one
  // (thread ids cannot tell, the system recycles them).
  thread_local int tasksOnThisThread = 0;
  int most = 0;
  for (int i = 0; i < 50; ++i) {
    auto task = inBackground([] {
      return ++tasksOnThisThread;
    });
    most = std::max(most, task.get());
  }
  EXPECT_GE(most, 10);  // 50 tasks on at most three kept threads (and rarely a spare one)
  EXPECT_EQ(tasksOnThisThread, 0);  // none ran on the caller's thread
}

}  // namespace
}  // namespace reamsim::csg
