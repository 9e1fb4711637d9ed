#pragma once
// Independent, read-only work over a range split between this thread and a second one: the machine has two
// cores, and the engine's other thread (the rounding check) is busy only part of a cut.
#include <cstddef>
#include "BackgroundTask.h"

namespace reamsim::csg {

// work(begin, end, part) over [0, n): in one piece (part 0) on this thread when each half would hold fewer
// than minPerThread items (handing work over costs a few µs, BackgroundTask.h), else the second half as part 1 on a second
// thread. Returns when both parts are done.
template <class Work>
void splitOverTwoThreads(std::size_t n, std::size_t minPerThread, Work&& work) {
  const std::size_t half = n / 2;
  if (half < minPerThread) {
    work(std::size_t(0), n, 0);
    return;
  }
  auto second = inBackground([&] { work(half, n, 1); });
  work(std::size_t(0), half, 0);
  second.get();
}

}  // namespace reamsim::csg
