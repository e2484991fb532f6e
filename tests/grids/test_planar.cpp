// Tests of grids/include/gridloc/grids/planar.hpp against brute force: the 2-D cross product
// is the z of the 3-D one, antisymmetric, and its sign says which way b turns from a.
#include "gridloc/grids/planar.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace gridloc {
namespace {

TEST(Planar, CrossIsTheZOfTheThreeDimensionalCrossProduct) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-100.0, 100.0);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector2d a(value(rng), value(rng)), b(value(rng), value(rng));
    const Eigen::Vector3d a3(a.x(), a.y(), 0.0), b3(b.x(), b.y(), 0.0);
    EXPECT_DOUBLE_EQ(cross(a, b), a3.cross(b3).z()) << k;
    EXPECT_EQ(cross(a, b), -cross(b, a)) << k;
    EXPECT_EQ(cross(a, a), 0.0) << k;
  }
}

TEST(Planar, CrossIsPositiveCounterClockwise) {
  const Eigen::Vector2d east(1.0, 0.0), north(0.0, 1.0);
  EXPECT_EQ(cross(east, north), 1.0);
  EXPECT_EQ(cross(north, east), -1.0);
  EXPECT_EQ(cross(Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(3.0, 4.0)), 8.0);  // the area
}

}  // namespace
}  // namespace gridloc
