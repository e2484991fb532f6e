// Tests of sensors/src/scan_disturbances.cpp: seed 004's range noise and outliers.
#include "gridloc/sensors/scan_disturbances.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace gridloc {
namespace {

std::vector<Eigen::Vector2d> ring_of_points(int n) {
  std::vector<Eigen::Vector2d> p;
  for (int k = 0; k < n; ++k) p.emplace_back(5.0 * std::cos(0.01 * k), 5.0 * std::sin(0.01 * k));
  return p;
}

TEST(ScanDisturbances, ScatterReplacesTheShareWithinTheSquare) {
  const auto clean = ring_of_points(400);
  const auto out = scatter_outliers(clean, 0.3, 3.0, 7);
  int changed = 0;
  for (std::size_t k = 0; k < clean.size(); ++k) {
    if (out[k] != clean[k]) {
      ++changed;
      EXPECT_LE(out[k].cwiseAbs().maxCoeff(), 3.0);
    }
  }
  EXPECT_EQ(changed, 120);
  EXPECT_EQ(out, scatter_outliers(clean, 0.3, 3.0, 7));  // seeded
  EXPECT_NE(out, scatter_outliers(clean, 0.3, 3.0, 8));
  test::expect_error([&] { scatter_outliers(clean, 1.5, 3.0, 1); }, {"share", "[0, 1]"});
  test::expect_error([&] { scatter_outliers(clean, 0.3, 0.0, 1); }, {"half_side_m"});
}

TEST(ScanDisturbances, AppearingObstaclesPullFourRunsCloser) {
  const auto clean = ring_of_points(400);
  const auto out = appear_obstacles(clean, 0.3, 3);
  int closer = 0;
  for (std::size_t k = 0; k < clean.size(); ++k) {
    const double f = out[k].norm() / clean[k].norm();
    if (f < 1.0) {
      ++closer;
      EXPECT_GE(f, 0.4 - 1e-12);
      EXPECT_LE(f, 0.8 + 1e-12);
    }
  }
  EXPECT_EQ(closer, 4 * 30);  // four runs of 0.3 * 400 / 4 points
  EXPECT_EQ(appear_obstacles(clean, 0.0, 3), clean);
  test::expect_error([&] { appear_obstacles(clean, -0.1, 1); }, {"share"});
}

TEST(ScanDisturbances, RangeNoiseTouchesReturnsOnly) {
  RangeScan s;
  s.max_range = 8.0;
  for (int k = 0; k < 1000; ++k) {
    s.angles.push_back(0.001 * k);
    s.ranges.push_back(k % 10 == 0 ? 8.0 : 4.0);
  }
  RangeScan n = s;
  add_range_noise(n, 0.02, 5);
  double sum2 = 0.0;
  int returns = 0;
  for (std::size_t k = 0; k < s.ranges.size(); ++k) {
    if (s.ranges[k] >= s.max_range) {
      EXPECT_EQ(n.ranges[k], s.ranges[k]);
    } else {
      sum2 += (n.ranges[k] - 4.0) * (n.ranges[k] - 4.0);
      ++returns;
    }
  }
  EXPECT_NEAR(std::sqrt(sum2 / returns), 0.02, 0.003);
  test::expect_error([&] { add_range_noise(n, -1.0, 1); }, {"sigma_m"});
}

}  // namespace
}  // namespace gridloc
