#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <new>
#include <numeric>
#include <string>

#include "reamsim/core/HugePageAllocator.h"

using namespace reamsim;

TEST(HugePageAllocator, LargeArraysAreHugePageAlignedAndMarked) {
  HugePageVector<double> v(3 << 20);  // 24 MiB
  std::iota(v.begin(), v.end(), 0.0);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::size_t(2) << 20), 0u);
  EXPECT_EQ(v[12345], 12345.0);
  EXPECT_EQ(v.back(), double((3 << 20) - 1));
#if defined(__linux__)
  if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) GTEST_SKIP() << "kernel without transparent huge pages";
  // MADV_HUGEPAGE shows as "hg" in the mapping's flags, whether or not the kernel has pages to give.
  const std::string flags = mappingFlags(v.data());
  ASSERT_FALSE(flags.empty()) << "no mapping found for the array";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  // How much is actually huge depends on the system: reported, not asserted.
  std::printf("huge pages under a 24 MiB array: %.1f MiB\n",
              double(hugePageBytesIn({{v.data(), v.size() * sizeof(double)}})) / (1 << 20));
#endif
}

TEST(HugePageAllocator, VectorsGrowCopyAndShrinkAcrossTheThreshold) {
  HugePageVector<std::uint32_t> v;
  for (std::uint32_t i = 0; i < 1'000'000; ++i) v.push_back(i * 3);  // crosses 1 MiB while growing
  HugePageVector<std::uint32_t> copy = v;
  ASSERT_EQ(copy.size(), 1'000'000u);
  for (std::size_t i = 0; i < copy.size(); i += 9973) ASSERT_EQ(copy[i], std::uint32_t(i * 3));
  v.resize(10);
  v.shrink_to_fit();  // back under the threshold: from the heap
  EXPECT_EQ(v.size(), 10u);
  EXPECT_EQ(v[9], 27u);
  HugePageVector<std::uint32_t> moved = std::move(copy);
  EXPECT_EQ(moved[999'999], 2'999'997u);
}

TEST(HugePageAllocator, SmallArraysComeFromTheHeap) {
  HugePageVector<int> v(100, 7);
  EXPECT_EQ(v[99], 7);
  EXPECT_EQ(hugePageBytesIn({{v.data(), 0}}), 0u);
}

TEST(HugePageAllocator, AnImpossibleSizeThrowsBadAlloc) {
  HugePageAllocator<char> a;
  EXPECT_THROW((void)a.allocate(std::size_t(-1) - 1000), std::bad_alloc);
  HugePageAllocator<double> d;
  EXPECT_THROW((void)d.allocate(std::size_t(-1) / 4), std::bad_array_new_length);
}
