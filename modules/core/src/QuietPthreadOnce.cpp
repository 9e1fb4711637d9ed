// pthread_once for ReamSim's own code, without a system call unless a thread is waiting.
//
// Why: CGAL's lazy exact kernel (Epeck) guards the exact evaluation of every lazy number and point with
// std::call_once, which libstdc++ runs through pthread_once, and glibc's pthread_once ends every first run
// with a futex wake whether or not any thread waits. A reaming cut evaluates ~700 lazy objects exactly, so
// that was ~700 system calls a cut; on this virtual machine each costs microseconds (the kernel's
// interrupt re-enabling was among the hottest symbols of a cut's profile): 3-13 % of a cut on the bundled
// scapula, depending on the machine's moment (docs/CSG.md, session 22). std::promise::set_value, which the
// cut's background tasks use, goes the same way.
//
// How: the executables and the GUI's plugins link with `--wrap=pthread_once` (cmake/ReamSimQuietOnce.cmake),
// so the calls in the objects linked into them, ours and CGAL's templates instantiated there, come here;
// other shared libraries (Qt, VTK, libstdc++ itself) keep glibc's. A flag is only ever used by one of the
// two: a once_flag lives in the code that calls it.
//
// States of the int behind pthread_once_t: 0 not run (PTHREAD_ONCE_INIT), 1 running, 5 running with a
// waiter, 2 done (glibc's "done" bit, so a glibc reader would agree). A waiter marks the flag before it
// sleeps, and the runner wakes only then. If the routine throws (std::call_once's callable may), the flag
// goes back to 0 and waiters wake to try again, as std::call_once requires. Not handled: thread
// cancellation inside the routine and fork() while it runs (glibc's fork generations); ReamSim does neither.
#include <linux/futex.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <climits>

namespace {
constexpr int kNotRun = 0, kRunning = 1, kDone = 2, kRunningWithWaiter = 5;

std::atomic<int>& stateOf(pthread_once_t* control) {
  static_assert(sizeof(pthread_once_t) == sizeof(std::atomic<int>), "pthread_once_t is an int");
  return *reinterpret_cast<std::atomic<int>*>(control);
}

void wakeAll(pthread_once_t* control) { syscall(SYS_futex, control, FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0); }

// Sleeps while the flag still reads `value` (returns at once otherwise, or on a signal: callers re-check).
void sleepWhile(pthread_once_t* control, int value) {
  syscall(SYS_futex, control, FUTEX_WAIT_PRIVATE, value, nullptr, nullptr, 0);
}

// Ends a run: the flag becomes `next`; waiters are woken only if there are any.
void finish(pthread_once_t* control, int next) {
  if (stateOf(control).exchange(next, std::memory_order_acq_rel) == kRunningWithWaiter) wakeAll(control);
}
}  // namespace

extern "C" int __wrap_pthread_once(pthread_once_t* control, void (*routine)(void)) {
  std::atomic<int>& state = stateOf(control);
  for (;;) {
    int seen = state.load(std::memory_order_acquire);
    if (seen == kDone) return 0;
    if (seen == kNotRun) {
      if (!state.compare_exchange_strong(seen, kRunning, std::memory_order_acquire)) continue;
      try {
        routine();
      } catch (...) {
        finish(control, kNotRun);
        throw;
      }
      finish(control, kDone);
      return 0;
    }
    // Another thread runs it: say so, then sleep until it is done (or has thrown).
    if (seen == kRunning && !state.compare_exchange_strong(seen, kRunningWithWaiter, std::memory_order_relaxed))
      continue;
    sleepWhile(control, kRunningWithWaiter);
  }
}
