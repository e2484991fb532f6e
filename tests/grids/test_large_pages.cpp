// Tests of grids/src/large_pages.cpp: the big grids' allocator gives usable, zeroed vectors of
// any size, large blocks aligned to a huge page on Linux.
#include "gridloc/grids/large_pages.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <numeric>

namespace gridloc {
namespace {

TEST(LargePages, VectorsOfEverySizeHoldWhatIsWritten) {
  for (const std::size_t n :
       {std::size_t{0}, std::size_t{1}, std::size_t{4095}, kLargeBlockBytes - 1, kLargeBlockBytes,
        kLargeBlockBytes + 4097, 3 * kLargeBlockBytes + 5}) {
    Int8Cells cells(n, 0);
    EXPECT_EQ(std::accumulate(cells.begin(), cells.end(), 0LL), 0) << n;
    for (std::size_t i = 0; i < n; ++i) cells[i] = static_cast<std::int8_t>(i % 101);
    long long expected = 0;
    for (std::size_t i = 0; i < n; ++i) expected += static_cast<long long>(i % 101);
    Int8Cells copy = cells;  // a second block, then both freed
    EXPECT_EQ(std::accumulate(copy.begin(), copy.end(), 0LL), expected) << n;
    cells.push_back(1);  // grows: a new block, the old one freed
    EXPECT_EQ(cells.size(), n + 1);
  }
}

TEST(LargePages, LargeBlocksStartOnAHugePage) {
  if (!maps_large_blocks()) GTEST_SKIP() << "large blocks come from operator new in this build";
  const Int8Cells cells(kLargeBlockBytes + 1, 0);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(cells.data()) % (std::uintptr_t{2} << 20), 0U);
}

}  // namespace
}  // namespace gridloc
