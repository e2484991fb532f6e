// Tests of sensors/src/local_grid.cpp: SparseLocalGrid's extent and mass.
#include "gridloc/sensors/local_grid.hpp"

#include <gtest/gtest.h>

namespace gridloc {
namespace {

TEST(SparseLocalGrid, EmptyGrid) {
  const SparseLocalGrid g;
  EXPECT_EQ(g.size(), 0u);
  EXPECT_EQ(g.extent(), 0);
  EXPECT_EQ(g.mass(), 0.0);
}

TEST(SparseLocalGrid, ExtentIsTheLargestAbsoluteOffset) {
  SparseLocalGrid g;
  g.dx = {0, -7, 3};
  g.dy = {-2, 1, 5};
  g.value = {0.5f, -0.25f, 0.125f};
  EXPECT_EQ(g.size(), 3u);
  EXPECT_EQ(g.extent(), 7);
  g.dy[2] = -9;
  EXPECT_EQ(g.extent(), 9);
}

TEST(SparseLocalGrid, MassIsTheSumOfAbsoluteValues) {
  SparseLocalGrid g;
  g.dx = {0, 1, 2};
  g.dy = {0, 0, 0};
  g.value = {0.5f, -0.25f, 0.125f};
  EXPECT_EQ(g.mass(), 0.875);
}

}  // namespace
}  // namespace gridloc
