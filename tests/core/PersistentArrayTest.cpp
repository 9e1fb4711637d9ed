#include <gtest/gtest.h>

#include <vector>

#include "reamsim/core/PersistentArray.h"

using namespace reamsim;
using Array = PersistentArray<int, 4>;

namespace {
std::vector<int> contents(const Array& a) {
  std::vector<int> v;
  a.forEach([&](int x) { v.push_back(x); });
  return v;
}
Array iota(int n) {
  Array a;
  for (int i = 0; i < n; ++i) a.push_back(i);
  return a;
}
}  // namespace

TEST(PersistentArray, BasicOperations) {
  Array a = iota(10);
  EXPECT_EQ(a.size(), 10u);
  EXPECT_EQ(a.chunkCount(), 3u);
  EXPECT_EQ(a[7], 7);
  EXPECT_EQ(a.back(), 9);
  a.set(7, 70);
  EXPECT_EQ(a.at(7), 70);
  EXPECT_THROW(a.at(10), std::out_of_range);
  EXPECT_THROW(a.set(10, 0), std::out_of_range);
  a.pop_back();
  a.pop_back();
  EXPECT_EQ(a.size(), 8u);
  EXPECT_EQ(a.chunkCount(), 2u);
  a.clear();
  EXPECT_TRUE(a.empty());
  EXPECT_THROW(a.pop_back(), std::out_of_range);
}

TEST(PersistentArray, OldVersionsNeverChange) {
  const Array v1 = iota(10);
  Array v2 = v1;
  v2.set(5, 50);
  v2.push_back(10);
  Array v3 = v2;
  v3.pop_back();
  v3.pop_back();
  v3.set(0, -1);
  Array v4 = v1;
  for (int i = 0; i < 10; ++i) v4.pop_back();
  EXPECT_EQ(contents(v1), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(contents(v2), (std::vector<int>{0, 1, 2, 3, 4, 50, 6, 7, 8, 9, 10}));
  EXPECT_EQ(contents(v3), (std::vector<int>{-1, 1, 2, 3, 4, 50, 6, 7, 8}));
  EXPECT_TRUE(v4.empty());
  // Refilling a popped array must not write into chunks v1 still uses.
  v4.push_back(100);
  EXPECT_EQ(v1[0], 0);
}

TEST(PersistentArray, SetCopiesOnlyTheTouchedChunk) {
  const Array v1 = iota(12);
  Array v2 = v1;
  for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(v1.chunkIdentity(c), v2.chunkIdentity(c));
  v2.set(5, 0);
  EXPECT_EQ(v1.chunkIdentity(0), v2.chunkIdentity(0));
  EXPECT_NE(v1.chunkIdentity(1), v2.chunkIdentity(1));
  EXPECT_EQ(v1.chunkIdentity(2), v2.chunkIdentity(2));
  // A second write to the now private chunk happens in place.
  const void* own = v2.chunkIdentity(1);
  v2.set(6, 0);
  EXPECT_EQ(v2.chunkIdentity(1), own);
}

TEST(PersistentArray, StorageVisitCountsTableAndChunks) {
  const Array a = iota(9);
  int blocks = 0;
  std::size_t bytes = 0;
  a.visitStorage([&](const void*, std::size_t b) {
    ++blocks;
    bytes += b;
  });
  EXPECT_EQ(blocks, 1 + 3);
  EXPECT_GE(bytes, 9 * sizeof(int));
}
