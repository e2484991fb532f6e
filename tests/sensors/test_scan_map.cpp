// Tests of the one-scan map's joined walls and the adaptive breakpoint gap
// (sensors/src/scan_map.cpp, sensors/src/breakpoints.cpp; issue 30).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/sensors/breakpoints.hpp"
#include "gridloc/sensors/scan_map.hpp"
#include "gridloc/sensors/segment_world.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A 181-beam front scan (1 degree apart) from the origin of `walls`.
RangeScan front_scan(const std::vector<WallSegment>& walls) {
  return simulate_segment_scan(walls, {0.0, 0.0, 0.0}, 181, -90.0 * kDeg, kDeg, 20.0);
}

/// The state of the cell holding world point (x, y).
CellState state(const OccupancyMap& map, double x, double y) {
  const GridGeometry& g = map.geometry;
  const Cell c = g.cell_of(x - g.origin.x(), y - g.origin.y());
  return map.at(c.ix, c.iy);
}

TEST(BreakpointGrowth, IsTheBorgesAldonRatioBelowHalfTheGrazingAngle) {
  EXPECT_DOUBLE_EQ(breakpoint_growth(kDeg, 10 * kDeg), std::sin(kDeg) / std::sin(9 * kDeg));
  EXPECT_DOUBLE_EQ(breakpoint_growth(kDeg, 10 * kDeg, 4.0), 4.0 * std::sin(kDeg));  // capped
  EXPECT_EQ(breakpoint_growth(6 * kDeg, 10 * kDeg), 0.0);  // beams too far apart
  EXPECT_EQ(breakpoint_growth(kDeg, 0.0), 0.0);            // no adaptive part
}

TEST(ScanMap, ASlantedWallIsDrawnWholeBetweenItsReturns) {
  // A wall 1 m to the left, running ahead: at 60-80 degrees off it, the returns lie 3-18 cm
  // apart along it.
  const RangeScan scan = front_scan({{{0.5, 1.0}, {8.0, 1.0}}});
  ScanMapOptions joined;
  ScanMapOptions alone = joined;
  alone.join_returns = false;
  const OccupancyMap with = scan_occupancy_map(scan, joined);
  const OccupancyMap without = scan_occupancy_map(scan, alone);
  int gaps_without = 0;
  for (double x = 1.0; x <= 5.0; x += 0.05) {
    EXPECT_EQ(state(with, x, 1.0), CellState::Occupied) << x;
    if (state(without, x, 1.0) != CellState::Occupied) ++gaps_without;
  }
  EXPECT_GT(gaps_without, 20);  // the returns alone leave most of the far wall open
  // The old signature draws the returns alone.
  EXPECT_EQ(scan_occupancy_map(scan, 0.05).cells, without.cells);
}

TEST(ScanMap, AnOcclusionEdgeIsNotJoined) {
  // A wall 2 m ahead to the right, another 4 m ahead to the left: the beam straight ahead
  // ends at (2, 0) on the first, the next one at (4, 0.07) on the second, 2 m apart across
  // free space, far beyond the breakpoint gap.
  const RangeScan scan = front_scan({{{2.0, -3.0}, {2.0, 0.02}}, {{4.0, 0.05}, {4.0, 3.0}}});
  const auto on_the_edge = [](double x) { return 0.07 * (x - 2.0) / 2.0; };
  ScanMapOptions options;
  const OccupancyMap map = scan_occupancy_map(scan, options);
  for (double x = 2.3; x <= 3.7; x += 0.1) {
    EXPECT_NE(state(map, x, on_the_edge(x)), CellState::Occupied) << x;
  }
  EXPECT_EQ(state(map, 2.02, -1.0), CellState::Occupied);
  EXPECT_EQ(state(map, 4.02, 1.0), CellState::Occupied);
  // A gap of 3 m joins them: the threshold, not the drawing, keeps them apart.
  options.join_gap_m = 3.0;
  const OccupancyMap joined = scan_occupancy_map(scan, options);
  for (double x = 2.3; x <= 3.7; x += 0.1) {
    EXPECT_EQ(state(joined, x, on_the_edge(x)), CellState::Occupied) << x;
  }
}

TEST(GrazingAngle, OutsideZeroToHalfPiIsNamed) {
  EXPECT_NO_THROW(check_grazing_angle(0.0, "x"));
  EXPECT_NO_THROW(check_grazing_angle(1.5, "x"));
  test::expect_error([] { check_grazing_angle(std::numbers::pi / 2, "IcpOptions.b"); },
                     {"IcpOptions.b must lie in [0, pi/2), got 1.57"});
  test::expect_error([] { check_grazing_angle(-0.1, "y"); }, {"y must lie in [0, pi/2)"});
  test::expect_error([] { check_grazing_angle(std::nan(""), "z"); }, {"z must lie"});
}

TEST(ScanMap, BadOptionsAreNamed) {
  const RangeScan scan = front_scan({{{3.0, -4.0}, {3.0, 4.0}}});
  auto expect_bad = [&](auto change, const char* field) {
    ScanMapOptions options;
    change(options);
    test::expect_error([&] { scan_occupancy_map(scan, options); }, {"scan_occupancy_map", field});
  };
  expect_bad([](ScanMapOptions& o) { o.resolution = 0.0; }, "resolution");
  expect_bad([](ScanMapOptions& o) { o.margin_m = -1.0; }, "margin");
  expect_bad([](ScanMapOptions& o) { o.join_gap_m = std::nan(""); }, "join_gap_m");
  expect_bad([](ScanMapOptions& o) { o.join_grazing_rad = 2.0; }, "join_grazing_rad");
}

}  // namespace
}  // namespace gridloc
