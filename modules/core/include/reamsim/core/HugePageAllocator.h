#pragma once
// An allocator for large, randomly read arrays (a 400k-face bone's hierarchy is ~60 MB): blocks of at
// least kHugePageThreshold bytes are mapped 2 MiB-aligned and marked for transparent huge pages, so a query
// that visits a few hundred nodes scattered over the array does not pay a page walk for each of them (on a
// virtual machine a TLB miss costs a two-level walk; first contact and min distance measured ~13% faster at
// 400k faces, docs/COLLISION.md).
// Smaller blocks come from operator new. Where huge pages are unavailable the hint is ignored and the block
// is an ordinary mapping.
#include <cstddef>
#include <new>
#include <string>
#include <vector>

namespace reamsim {

namespace detail {
constexpr std::size_t kHugePageThreshold = std::size_t(1) << 20;  // 1 MiB: smaller arrays stay on the heap
void* allocateHugePageBlock(std::size_t bytes);                   // throws std::bad_alloc
void freeHugePageBlock(void* p, std::size_t bytes) noexcept;
}  // namespace detail

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{alignof(T) > 16 ? alignof(T) : 16};  // small blocks, heap
  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= detail::kHugePageThreshold) return static_cast<T*>(detail::allocateHugePageBlock(bytes));
    return static_cast<T*>(::operator new(bytes, kAlign));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= detail::kHugePageThreshold) {
      detail::freeHugePageBlock(p, bytes);
    } else {
      ::operator delete(p, kAlign);
    }
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

// Bytes backed by huge pages in the mappings that hold the given ranges (each mapping counted once), from
// /proc/self/smaps; 0 where the system gives none, or off Linux. A report for benchmarks: the kernel may
// merge neighbouring mappings, so the figure can include their pages too.
struct MemoryRange {
  const void* data;
  std::size_t bytes;
};
std::size_t hugePageBytesIn(const std::vector<MemoryRange>& ranges);
// The "VmFlags:" line of the mapping that holds p ("hg" in it: marked for huge pages); "" when no mapping is
// found, or off Linux.
std::string mappingFlags(const void* p);

}  // namespace reamsim
