// Tests of sensors/src/scan_sim.cpp: the grid laser simulator (exact ray casting, seeded
// noise, no return at max range) and its input validation.
#include "gridloc/sensors/scan_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kRes = 0.1;

/// A 4 m x 2 m map at 0.1 m, origin (0, 0): Occupied rows y in [0, 0.1] (south wall) and
/// [1.9, 2.0] (north wall) and column x in [3.9, 4.0] (east wall); the west side is open, so
/// a beam going west leaves the map.
OccupancyMap box_map() {
  GridGeometry g;
  g.resolution = kRes;
  g.width = 40;
  g.height = 20;
  OccupancyMap m(g, CellState::Free);
  for (int x = 0; x < g.width; ++x) {
    m.at(x, 0) = CellState::Occupied;
    m.at(x, g.height - 1) = CellState::Occupied;
  }
  for (int y = 0; y < g.height; ++y) m.at(g.width - 1, y) = CellState::Occupied;
  return m;
}

// Four beams: k = 0 at -pi (west), 1 at -pi/2 (south), 2 at 0 (east), 3 at +pi/2 (north).
constexpr int kWest = 0, kSouth = 1, kEast = 2, kNorth = 3;
const Pose2 kPose{1.03, 1.07, 0.0};

TEST(SimulateScan, BeamAnglesSpanTheCircleFromMinusPi) {
  const RangeScan s = simulate_scan(box_map(), kPose, 8, 10.0, 0.0, 1);
  ASSERT_EQ(s.angles.size(), 8u);
  ASSERT_EQ(s.ranges.size(), 8u);
  EXPECT_DOUBLE_EQ(s.max_range, 10.0);
  for (int k = 0; k < 8; ++k)
    EXPECT_DOUBLE_EQ(s.angles[k], -std::numbers::pi + k * std::numbers::pi / 4);
}

TEST(SimulateScan, BeamsAtWallsReadTheirDistance) {
  const RangeScan s = simulate_scan(box_map(), kPose, 4, 10.0, 0.0, 1);
  EXPECT_NEAR(s.ranges[kEast], 3.9 - kPose.x, kRes);
  EXPECT_NEAR(s.ranges[kSouth], kPose.y - 0.1, kRes);
  EXPECT_NEAR(s.ranges[kNorth], 1.9 - kPose.y, kRes);
  // The west side is open: the beam leaves the map with no return.
  EXPECT_EQ(s.ranges[kWest], 10.0);
}

TEST(SimulateScan, HeadingTurnsTheBeams) {
  // Facing north, the beam at -pi/2 (robot frame) points east.
  const RangeScan s =
      simulate_scan(box_map(), {kPose.x, kPose.y, std::numbers::pi / 2}, 4, 10.0, 0.0, 1);
  EXPECT_NEAR(s.ranges[kSouth], 3.9 - kPose.x, kRes);
  EXPECT_NEAR(s.ranges[kEast], 1.9 - kPose.y, kRes);
  EXPECT_NEAR(s.ranges[kWest], kPose.y - 0.1, kRes);
  EXPECT_EQ(s.ranges[kNorth], 10.0);
}

TEST(SimulateScan, NoWallWithinMaxRangeReadsExactlyMaxRange) {
  // The east wall is 2.87 m away, beyond a 2 m max range; noise does not touch no-returns.
  for (double sigma : {0.0, 0.05}) {
    const RangeScan s = simulate_scan(box_map(), kPose, 4, 2.0, sigma, 9);
    EXPECT_EQ(s.ranges[kEast], 2.0) << "sigma " << sigma;
    EXPECT_EQ(s.ranges[kWest], 2.0) << "sigma " << sigma;
    EXPECT_LT(s.ranges[kNorth], 2.0) << "sigma " << sigma;
  }
}

TEST(SimulateScan, SameSeedSameScanOtherSeedOtherNoise) {
  const OccupancyMap m = box_map();
  const RangeScan a = simulate_scan(m, kPose, 360, 8.0, 0.02, 42);
  const RangeScan b = simulate_scan(m, kPose, 360, 8.0, 0.02, 42);
  const RangeScan c = simulate_scan(m, kPose, 360, 8.0, 0.02, 43);
  EXPECT_EQ(a.angles, b.angles);
  EXPECT_EQ(a.ranges, b.ranges);
  EXPECT_NE(a.ranges, c.ranges);
  // Noise stays within a few sigma of the noise-free ranges, clamped into [0, max_range].
  const RangeScan exact = simulate_scan(m, kPose, 360, 8.0, 0.0, 42);
  for (std::size_t k = 0; k < a.ranges.size(); ++k) {
    EXPECT_NEAR(a.ranges[k], exact.ranges[k], 6 * 0.02) << "beam " << k;
    EXPECT_GE(a.ranges[k], 0.0);
    EXPECT_LE(a.ranges[k], 8.0);
  }
}

TEST(SimulateScan, BadInputIsNamed) {
  const OccupancyMap m = box_map();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  test::expect_error([&] { simulate_scan(m, kPose, 0, 8.0, 0.0, 1); }, {"beams", "0"});
  test::expect_error([&] { simulate_scan(m, kPose, -3, 8.0, 0.0, 1); }, {"beams", "-3"});
  for (double r : {0.0, -1.0, inf, nan}) {
    test::expect_error([&] { simulate_scan(m, kPose, 4, r, 0.0, 1); }, {"max_range"});
  }
  for (double s : {-0.01, nan, inf}) {
    test::expect_error([&] { simulate_scan(m, kPose, 4, 8.0, s, 1); }, {"sigma_m"});
  }
  test::expect_error([&] { simulate_scan(m, {nan, 1.0, 0.0}, 4, 8.0, 0.0, 1); }, {"pose"});
  test::expect_error([&] { simulate_scan(m, {1.0, 1.0, inf}, 4, 8.0, 0.0, 1); }, {"pose"});
}

}  // namespace
}  // namespace gridloc
