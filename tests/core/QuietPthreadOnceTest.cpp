// The quiet pthread_once (modules/core/src/QuietPthreadOnce.cpp) that the executables and these tests link
// in place of glibc's: that it is the one in use, and that std::call_once keeps its guarantees through it
// (one run, its effects seen by every caller, waiters blocked until it ends, a throwing run retried).
#include <gtest/gtest.h>
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#ifdef REAMSIM_QUIET_PTHREAD_ONCE
extern "C" int __wrap_pthread_once(pthread_once_t*, void (*)(void));
#endif

namespace {

using namespace std::chrono_literals;

TEST(QuietPthreadOnce, IsTheOneThisExecutableCalls) {
#ifdef REAMSIM_QUIET_PTHREAD_ONCE
  // With --wrap=pthread_once every reference to pthread_once in this executable's objects names the wrapper.
  EXPECT_EQ(reinterpret_cast<void*>(&pthread_once), reinterpret_cast<void*>(&__wrap_pthread_once));
#else
  GTEST_SKIP() << "built without the quiet pthread_once (sanitizer build or REAMSIM_QUIET_ONCE=OFF)";
#endif
}

// Many flags raced by several threads, as CGAL's lazy points are by the cut's two threads: each routine
// runs once and every caller sees what it wrote (a plain write, published by the flag alone).
TEST(QuietPthreadOnce, EachFlagRunsOnceAndEveryCallerSeesItsEffect) {
  constexpr int kFlags = 20000, kThreads = 4;
  struct Slot {
    std::once_flag flag;
    std::atomic<int> runs{0};
    int value = 0;
  };
  std::vector<std::unique_ptr<Slot>> slots;
  for (int i = 0; i < kFlags; ++i) slots.push_back(std::make_unique<Slot>());
  std::atomic<int> wrongReads{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < kFlags; ++k) {
        const int i = (t % 2 == 0) ? k : kFlags - 1 - k;  // half the threads walk backwards: they meet
        Slot& s = *slots[i];
        std::call_once(s.flag, [&] {
          s.runs.fetch_add(1);
          s.value = i + 1;
        });
        if (s.value != i + 1) wrongReads.fetch_add(1);
      }
    });
  for (auto& th : threads) th.join();
  for (int i = 0; i < kFlags; ++i) ASSERT_EQ(slots[i]->runs.load(), 1) << "flag " << i;
  EXPECT_EQ(wrongReads.load(), 0);
}

// A caller that arrives while the routine runs waits for it and returns only after it has ended.
TEST(QuietPthreadOnce, CallersWaitForARunningRoutine) {
  std::once_flag flag;
  std::atomic<bool> started{false}, finished{false};
  std::thread runner([&] {
    std::call_once(flag, [&] {
      started = true;
      std::this_thread::sleep_for(50ms);
      finished = true;
    });
  });
  while (!started) std::this_thread::yield();
  std::vector<std::thread> waiters;
  std::atomic<int> sawUnfinished{0}, ranAgain{0};
  for (int i = 0; i < 3; ++i)
    waiters.emplace_back([&] {
      std::call_once(flag, [&] { ranAgain.fetch_add(1); });
      if (!finished) sawUnfinished.fetch_add(1);
    });
  runner.join();
  for (auto& w : waiters) w.join();
  EXPECT_EQ(sawUnfinished.load(), 0);
  EXPECT_EQ(ranAgain.load(), 0);
}

// std::call_once: a routine that throws leaves the flag unset; the next caller runs its own routine.
TEST(QuietPthreadOnce, ARoutineThatThrowsIsRunAgain) {
  std::once_flag flag;
  int runs = 0;
  EXPECT_THROW(std::call_once(flag,
                              [&] {
                                ++runs;
                                throw std::runtime_error("first try fails");
                              }),
               std::runtime_error);
  std::call_once(flag, [&] { ++runs; });
  std::call_once(flag, [&] { ++runs; });
  EXPECT_EQ(runs, 2);
}

// ... also when another thread is already waiting on it: the waiter wakes and runs its routine.
TEST(QuietPthreadOnce, AWaiterRunsItsRoutineWhenTheRunningOneThrows) {
  std::once_flag flag;
  std::atomic<bool> started{false};
  std::atomic<int> waiterRuns{0};
  std::thread thrower([&] {
    try {
      std::call_once(flag, [&] {
        started = true;
        std::this_thread::sleep_for(50ms);
        throw std::runtime_error("fails while a waiter sleeps");
      });
    } catch (const std::runtime_error&) {
    }
  });
  while (!started) std::this_thread::yield();
  std::thread waiter([&] { std::call_once(flag, [&] { waiterRuns.fetch_add(1); }); });
  thrower.join();
  waiter.join();
  EXPECT_EQ(waiterRuns.load(), 1);
}

}  // namespace
