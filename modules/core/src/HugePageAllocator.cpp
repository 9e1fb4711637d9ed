#include "reamsim/core/HugePageAllocator.h"

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace reamsim::detail {

namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
std::size_t roundUp(std::size_t bytes, std::size_t to) { return (bytes + to - 1) / to * to; }
}  // namespace

#if defined(__linux__)
// Mapped with one huge page of slack and trimmed to a 2 MiB boundary: a huge page needs an aligned range.
// The hint is given before the first touch, so the pages are huge from their first fault.
void* allocateHugePageBlock(std::size_t bytes) {
  if (bytes > std::size_t(-1) / 2) throw std::bad_alloc();  // the rounding and the slack must not wrap
  const std::size_t size = roundUp(bytes, kHugePage);
  void* raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = roundUp(start, kHugePage);
  if (aligned > start) munmap(raw, aligned - start);
  const std::uintptr_t end = start + size + kHugePage;
  if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
#if defined(MADV_HUGEPAGE)
  (void)madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);  // a hint: failure is harmless
#endif
  return reinterpret_cast<void*>(aligned);
}

void freeHugePageBlock(void* p, std::size_t bytes) noexcept {
  if (p) munmap(p, roundUp(bytes, kHugePage));
}
#else
void* allocateHugePageBlock(std::size_t bytes) {
  return ::operator new(bytes, std::align_val_t(kHugePage));
}
void freeHugePageBlock(void* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kHugePage)); }
#endif

}  // namespace reamsim::detail

namespace reamsim {

namespace {

// Walks /proc/self/smaps: `enter(lo, hi)` at each mapping's header line ("start-end perms offset dev inode
// [path]", addresses in hex) says whether the mapping's detail lines go to `line`.
template <class Enter, class Line>
void walkSmaps(Enter&& enter, Line&& line) {
  std::ifstream smaps("/proc/self/smaps");
  std::string text;
  bool inside = false;
  while (std::getline(smaps, text)) {
    std::uintptr_t a = 0, b = 0;
    char dash = 0;
    std::istringstream header(text);
    if (header >> std::hex >> a >> dash >> b && dash == '-') {
      inside = enter(a, b);
      continue;
    }
    if (inside) line(text);
  }
}

}  // namespace

std::size_t hugePageBytesIn(const std::vector<MemoryRange>& ranges) {
#if defined(__linux__)
  std::size_t total = 0;
  walkSmaps(
      [&](std::uintptr_t a, std::uintptr_t b) {
        for (const MemoryRange& r : ranges) {
          const auto lo = reinterpret_cast<std::uintptr_t>(r.data);
          if (r.bytes > 0 && a < lo + r.bytes && lo < b) return true;
        }
        return false;
      },
      [&](const std::string& text) {
        if (text.rfind("AnonHugePages:", 0) != 0) return;
        std::istringstream value(text.substr(14));
        std::size_t kb = 0;
        value >> kb;
        total += kb * 1024;
      });
  return total;
#else
  (void)ranges;
  return 0;
#endif
}

std::string mappingFlags(const void* p) {
#if defined(__linux__)
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::string flags;
  walkSmaps([&](std::uintptr_t a, std::uintptr_t b) { return a <= at && at < b; },
            [&](const std::string& text) {
              if (text.rfind("VmFlags:", 0) == 0) flags = text;
            });
  return flags;
#else
  (void)p;
  return "";
#endif
}

}  // namespace reamsim
