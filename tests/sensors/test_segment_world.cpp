// Tests of sensors/src/segment_world.cpp: exact ray casting against wall segments, the seed
// 004 hallway scene, and input validation.
#include "gridloc/sensors/segment_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(SegmentWorld, ReadsTheNearestWallAndMaxRangeWithoutOne) {
  // A wall x = 2 for y in [-1, 1], and a short one x = 1 for y in [0.4, 1].
  const std::vector<WallSegment> walls{{{2, -1}, {2, 1}}, {{1, 0.4}, {1, 1}}};
  const double up = std::atan2(0.5, 1.0);  // through (1, 0.5) on the short wall
  const RangeScan s = simulate_segment_scan(walls, {0, 0, 0}, 4, 0.0, up, 8.0);
  ASSERT_EQ(s.angles.size(), 4u);
  ASSERT_EQ(s.ranges.size(), 4u);
  EXPECT_DOUBLE_EQ(s.max_range, 8.0);
  EXPECT_DOUBLE_EQ(s.angles[1], up);
  EXPECT_NEAR(s.ranges[0], 2.0, 1e-12);              // passes under the short wall
  EXPECT_NEAR(s.ranges[1], std::sqrt(1.25), 1e-12);  // the short wall, not x = 2
  EXPECT_EQ(s.ranges[3], 8.0);                       // above both walls: no return
  // Too far for a 1.5 m sensor: exactly max_range.
  EXPECT_EQ(simulate_segment_scan(walls, {0, 0, 0}, 1, 0.0, 0.1, 1.5).ranges[0], 1.5);
  // Behind the robot: no return.
  EXPECT_EQ(simulate_segment_scan(walls, {0, 0, kPi}, 1, 0.0, 0.1, 8.0).ranges[0], 8.0);
}

TEST(SegmentWorld, PoseMovesAndTurnsTheBeams) {
  const std::vector<WallSegment> walls{{{2, -1}, {2, 1}}};
  // From (0.5, 0.3) facing north, the beam at -90 deg points east: 1.5 m to the wall.
  const RangeScan s = simulate_segment_scan(walls, {0.5, 0.3, kPi / 2}, 2, -kPi / 2, kPi / 2, 8.0);
  EXPECT_NEAR(s.ranges[0], 1.5, 1e-12);
  EXPECT_EQ(s.ranges[1], 8.0);
}

TEST(SegmentWorld, Seed004HallwayDistances) {
  const auto hallway = seed004_hallway();
  EXPECT_EQ(hallway.size(), 20u);
  // From the origin: east end wall at x = 6, west end at x = -4 (the column lies above
  // y = 0.2), top and bottom walls at y = +-1.
  const RangeScan s = simulate_segment_scan(hallway, {0, 0, 0}, 4, -kPi, kPi / 2, 8.0);
  EXPECT_NEAR(s.ranges[0], 4.0, 1e-12);
  EXPECT_NEAR(s.ranges[1], 1.0, 1e-12);
  EXPECT_NEAR(s.ranges[2], 6.0, 1e-12);
  EXPECT_NEAR(s.ranges[3], 1.0, 1e-12);
  // From (1.5, 0) looking up into the door recess (top at y = 1.6), and from (-2.35, 0) up at
  // the column (bottom face at y = 0.2).
  EXPECT_NEAR(simulate_segment_scan(hallway, {1.5, 0, 0}, 1, kPi / 2, 1, 8.0).ranges[0], 1.6,
              1e-12);
  EXPECT_NEAR(simulate_segment_scan(hallway, {-2.35, 0, 0}, 1, kPi / 2, 1, 8.0).ranges[0], 0.2,
              1e-12);
}

TEST(SegmentWorld, BadInputIsNamed) {
  const auto w = seed004_hallway();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  test::expect_error([&] { simulate_segment_scan(w, {}, 0, 0.0, 0.01, 8.0); }, {"beams", "0"});
  for (double step : {0.0, -0.01, nan, inf}) {
    test::expect_error([&] { simulate_segment_scan(w, {}, 4, 0.0, step, 8.0); }, {"angle_step"});
  }
  for (double r : {0.0, -1.0, nan, inf}) {
    test::expect_error([&] { simulate_segment_scan(w, {}, 4, 0.0, 0.01, r); }, {"max_range"});
  }
  test::expect_error([&] { simulate_segment_scan(w, {}, 4, nan, 0.01, 8.0); }, {"first_angle"});
  test::expect_error([&] { simulate_segment_scan(w, {0, inf, 0}, 4, 0.0, 0.01, 8.0); }, {"pose"});
  test::expect_error([&] { simulate_segment_scan(w, {0, 0, nan}, 4, 0.0, 0.01, 8.0); }, {"pose"});
}

}  // namespace
}  // namespace gridloc
