#include "MachineSpeed.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <random>

#include <sys/mman.h>

namespace reamsim::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Memory of its own from the system, returned when done: the probe's 64 MiB must not pass through the
// allocator, which would keep the pages and hand them, already mapped, to the benchmark that follows.
template <class T>
struct Mapped {
  explicit Mapped(std::size_t count) : bytes(count * sizeof(T)) {
    void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    data = p == MAP_FAILED ? nullptr : static_cast<T*>(p);
  }
  ~Mapped() {
    if (data) ::munmap(data, bytes);
  }
  Mapped(const Mapped&) = delete;
  Mapped& operator=(const Mapped&) = delete;
  std::size_t bytes;
  T* data = nullptr;
};

double nanosSince(Clock::time_point t0, std::size_t per) {
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / double(per);
}

// One dependent chain of multiply-adds: each waits for the last, so the time per step is the unit's
// latency in the core's clock.
double fmaNanos() {
  constexpr std::size_t kSteps = 10'000'000;
  volatile double seed = 1.0;
  double x = seed;
  const auto t0 = Clock::now();
  for (std::size_t i = 0; i < kSteps; ++i) x = x * 0.9999999 + 1e-7;
  const double ns = nanosSince(t0, kSteps);
  seed = x;  // keeps the chain
  return ns;
}

// A dependent load through `bytes` of cache lines visited in a random order linked into one cycle, so that
// neither the prefetchers nor the out-of-order core can run ahead: each load waits for the one before.
double loadNanos(std::size_t bytes, std::size_t loads) {
  struct alignas(64) Line {
    std::uint32_t next;
  };
  const std::size_t n = bytes / sizeof(Line);
  const Mapped<Line> lineMap(n);
  const Mapped<std::uint32_t> orderMap(n);
  Line* lines = lineMap.data;
  std::uint32_t* order = orderMap.data;
  if (!lines || !order) return -1;
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
  std::mt19937_64 rng(7);
  std::shuffle(order, order + n, rng);
  for (std::size_t i = 0; i < n; ++i) lines[order[i]].next = order[(i + 1) % n];
  std::uint32_t at = order[0];
  // A first stretch of the walk: what fits in a cache is in it (the fill above has mapped every page).
  for (std::size_t i = 0; i < std::min(n, loads); ++i) at = lines[at].next;
  const auto t0 = Clock::now();
  for (std::size_t i = 0; i < loads; ++i) at = lines[at].next;
  const double ns = nanosSince(t0, loads);
  volatile std::uint32_t sink = at;
  (void)sink;
  return ns;
}

}  // namespace

nlohmann::json machineSpeed() {
  const auto t0 = Clock::now();
  nlohmann::json j;
  j["fma_ns"] = fmaNanos();
  j["load_ns"] = {{"256KiB", loadNanos(std::size_t(256) << 10, 1'000'000)},
                  {"8MiB", loadNanos(std::size_t(8) << 20, 300'000)},
                  {"64MiB", loadNanos(std::size_t(64) << 20, 200'000)}};
  j["probe_ms"] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  return j;
}

}  // namespace reamsim::cli
