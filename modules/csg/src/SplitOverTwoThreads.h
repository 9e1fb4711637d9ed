#pragma once
// Independent, read-only work over a range split between this thread and a second one: the machine has two
// cores, and the engine's other thread (the rounding check) is busy only part of a cut.
#include <algorithm>
#include <atomic>
#include <cstddef>

#include "BackgroundTask.h"

namespace reamsim::csg {

// work(begin, end, part) over [0, n): in one piece (part 0) on this thread when each half would hold fewer
// than minPerThread items (handing work over costs a few µs, BackgroundTask.h), else in chunks that this
// thread (part 0) and a second one (part 1) take in turn, so that a second thread that starts late (its core
// busy with another process) leaves its share to this one instead of making it wait. A part may get
// several chunks, in no fixed order: work must write per item or per part (and merge parts without regard
// to order). Returns when every chunk is done.
template <class Work>
void splitOverTwoThreads(std::size_t n, std::size_t minPerThread, Work&& work) {
  if (n / 2 < minPerThread) {
    work(std::size_t(0), n, 0);
    return;
  }
  const std::size_t chunk = std::max<std::size_t>(16, minPerThread / 8);
  std::atomic<std::size_t> next{0};
  auto run = [&](int part) {
    for (std::size_t begin; (begin = next.fetch_add(chunk, std::memory_order_relaxed)) < n;)
      work(begin, std::min(n, begin + chunk), part);
  };
  auto second = inBackground([&] { run(1); });
  run(0);
  second.get();  // not started yet: it runs here and finds no chunk left
}

}  // namespace reamsim::csg
