// The grid overlay (seed 002 §IV on occupancy maps): OI, internal cells and U on hand-made
// rooms whose answers are known, checked against brute force; sampling of OI and U.
#include "gridloc/engine/disambiguation/grid_overlay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;
using test::walled_room;

/// The start-frame centres of the cells of `overlay` whose byte in `set` is 1.
std::vector<Eigen::Vector2d> centers_of(const GridOverlay& overlay,
                                        const std::vector<std::uint8_t>& set) {
  std::vector<Eigen::Vector2d> centers;
  for (int iy = 0; iy < overlay.grid.height; ++iy) {
    for (int ix = 0; ix < overlay.grid.width; ++ix) {
      if (set[overlay.grid.index(ix, iy)]) centers.push_back(overlay.cell_center({ix, iy}));
    }
  }
  return centers;
}

/// A 40 x 30-cell room at 0.1 m (interior 38 x 28 cells, x in [0.1, 3.9], y in [0.1, 2.9])
/// seen from two starts 1 m apart along x.
struct ShiftedRooms {
  OccupancyMap map = walled_room(40, 30, 0.1, {0.0, 0.0});
  std::vector<Pose2> hypotheses{{2.0, 1.5, 0.0}, {3.0, 1.5, 0.0}};
};

TEST(GridOverlay, ShiftedRoomsShrinkOiByTheShift) {
  const ShiftedRooms rooms;
  const GridOverlay overlay = make_grid_overlay(rooms.map, rooms.hypotheses, 0.55);
  // Start frame: the first map spans x in [-1.9, 1.9], the second [-2.9, 0.9]; OI = [-1.9, 0.9]
  EXPECT_EQ(overlay.oi_count, 28 * 28);
  EXPECT_EQ(overlay.oi_count, 38 * 28 - 10 * 28);  // the room less 1 m on one side
  for (const Eigen::Vector2d& c : centers_of(overlay, overlay.in_oi)) {
    EXPECT_GT(c.x(), -1.9);
    EXPECT_LT(c.x(), 0.9);
    EXPECT_GT(c.y(), -1.4);
    EXPECT_LT(c.y(), 1.4);
  }
  EXPECT_TRUE(overlay.oi_contains({0.0, 0.0}));
  EXPECT_FALSE(overlay.oi_contains({1.0, 0.0}));  // only the first map is free there
  EXPECT_EQ(overlay.hypotheses.size(), 2u);
}

TEST(GridOverlay, ShiftedRoomsInternalCellsFaceTheOtherMapsFreeSpace) {
  const ShiftedRooms rooms;
  const GridOverlay overlay = make_grid_overlay(rooms.map, rooms.hypotheses, 0.55);
  // Beyond OI's east column the first map is free, beyond its west column the second; its
  // north and south rows face walls in both maps.
  EXPECT_EQ(overlay.internal_count, 2 * 28);
  for (const Eigen::Vector2d& c : centers_of(overlay, overlay.internal)) {
    EXPECT_TRUE(std::abs(c.x() - 0.85) < 1e-9 || std::abs(c.x() + 1.85) < 1e-9) << c.x();
  }
}

TEST(GridOverlay, UsefulCellsAreTheOiCellsWithinRangeOfAnInternalCell) {
  const ShiftedRooms rooms;
  const double range = 0.55;
  const GridOverlay overlay = make_grid_overlay(rooms.map, rooms.hypotheses, range);
  const std::vector<Eigen::Vector2d> internal = centers_of(overlay, overlay.internal);
  int expected = 0;  // OI is convex: every OI cell sees every internal cell
  for (int iy = 0; iy < overlay.grid.height; ++iy) {
    for (int ix = 0; ix < overlay.grid.width; ++ix) {
      const std::size_t i = overlay.grid.index(ix, iy);
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& c : internal) {
        nearest = std::min(nearest, (c - overlay.cell_center({ix, iy})).norm());
      }
      const bool in_reach = overlay.in_oi[i] && nearest <= range;
      expected += in_reach ? 1 : 0;
      EXPECT_EQ(overlay.useful[i] != 0, in_reach) << ix << " " << iy;
    }
  }
  EXPECT_EQ(overlay.useful_count, expected);
  EXPECT_EQ(expected, 2 * 6 * 28);  // six columns on each internal side
}

/// Whether the segment between two start-frame points runs through OI cells only (brute
/// force: samples every 1/50 cell).
bool sees_through_oi(const GridOverlay& overlay, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b) {
  const int samples = 1 + static_cast<int>(50.0 * (b - a).norm() / overlay.grid.resolution);
  for (int k = 0; k <= samples; ++k) {
    if (!overlay.oi_contains(a + (b - a) * (static_cast<double>(k) / samples))) return false;
  }
  return true;
}

TEST(GridOverlay, UsefulCellsMatchBruteForceVisibilityAmongPillars) {
  OccupancyMap map = walled_room(40, 30, 0.1, {0.0, 0.0});
  std::mt19937 rng(11);
  for (int pillar = 0; pillar < 6; ++pillar) {
    const int px = test::uniform_int(rng, 3, 35), py = test::uniform_int(rng, 3, 25);
    map.at(px, py) = map.at(px + 1, py) = map.at(px, py + 1) = CellState::Occupied;
  }
  const std::vector<Pose2> hypotheses{{2.05, 1.55, 0.0}, {2.45, 1.55, 0.0}};
  const double range = 0.45;
  const GridOverlay overlay = make_grid_overlay(map, hypotheses, range, {0.05, 0.05});
  const std::vector<Eigen::Vector2d> internal = centers_of(overlay, overlay.internal);
  int visible = 0, visible_in_u = 0;
  for (const Eigen::Vector2d& c : centers_of(overlay, overlay.in_oi)) {
    bool within = false, seen = false;
    for (const Eigen::Vector2d& s : internal) {
      if ((s - c).norm() > range) continue;
      within = true;
      seen = seen || sees_through_oi(overlay, s, c);
    }
    const bool in_u =
        overlay.useful[overlay.grid.index(overlay.cell_of(c).ix, overlay.cell_of(c).iy)];
    if (in_u) {
      EXPECT_TRUE(within) << c.transpose();  // never beyond the range
    }
    visible += seen ? 1 : 0;
    visible_in_u += seen && in_u ? 1 : 0;
  }
  ASSERT_GT(visible, 100);
  EXPECT_GE(visible_in_u, 0.99 * visible);  // rays at discrete angles: all but a few
  EXPECT_LT(overlay.useful_count, overlay.oi_count);
}

TEST(GridOverlay, UnlimitedRangeMakesAConvexOiUseful) {
  const ShiftedRooms rooms;
  const GridOverlay overlay =
      make_grid_overlay(rooms.map, rooms.hypotheses, std::numeric_limits<double>::infinity());
  EXPECT_EQ(overlay.useful_count, overlay.oi_count);
}

TEST(GridOverlay, RotatedHypothesesOfASquareRoomKeepTheWholeRoom) {
  const OccupancyMap map = walled_room(30, 30, 0.1, {0.0, 0.0});  // interior 28 x 28
  const double half_pi = std::numbers::pi / 2.0;
  const std::vector<Pose2> hypotheses{{1.5, 1.5, 0.0}, {1.5, 1.5, half_pi}, {1.5, 1.5, -half_pi}};
  const GridOverlay overlay = make_grid_overlay(map, hypotheses, 1.0);
  EXPECT_EQ(overlay.oi_count, 28 * 28);
  EXPECT_EQ(overlay.internal_count, 0);  // every map has walls where OI ends
  EXPECT_EQ(overlay.useful_count, 0);
}

TEST(GridOverlay, ArbitraryHeadingOverlapIsTheRectanglesIntersection) {
  // Heading 0.7 rad: the room appears rotated in the start frame; the second start lies 1 m
  // ahead of the first, so OI is the room intersected with itself moved by
  // R(0.7) (1, 0) = (0.765, 0.644) m in the room's frame: (3.8 - 0.765) x (2.8 - 0.644) m.
  const OccupancyMap map = walled_room(40, 30, 0.1, {0.0, 0.0});
  const Pose2 first{2.0, 1.5, 0.7};
  const Pose2 second = compose(first, {1.0, 0.0, 0.0});
  const double expected = (3.8 - std::cos(0.7)) * (2.8 - std::sin(0.7)) / (0.1 * 0.1);
  const GridOverlay overlay =
      make_grid_overlay(map, {first, second}, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(overlay.oi_count, expected, 20.0);      // cells cut by the rotated sides
  EXPECT_GT(overlay.internal_count, 60);              // every side faces the other map
  EXPECT_EQ(overlay.useful_count, overlay.oi_count);  // convex, unlimited range
  const GridOverlay alone = make_grid_overlay(map, {first, first}, 1.0);
  EXPECT_NEAR(alone.oi_count, 38 * 28, 15.0);
  EXPECT_EQ(alone.internal_count, 0);
}

TEST(GridOverlay, FollowsTheMapsOriginAndYaw) {
  const double yaw = 0.3;
  OccupancyMap map = walled_room(30, 20, 0.1, {1.0, -2.0});
  map.geometry.yaw = yaw;
  // The start at the room's grid point (1.5, 1.0), heading along the grid's x axis: the
  // start frame is the room's grid frame shifted, so OI is the whole interior.
  const Pose2 grid_point = map.geometry.to_world_frame({1.5, 1.0, 0.0});
  const GridOverlay overlay = make_grid_overlay(map, {grid_point}, 1.0);
  EXPECT_EQ(overlay.oi_count, 28 * 18);
  EXPECT_EQ(overlay.internal_count, 0);
  EXPECT_TRUE(overlay.oi_contains({1.35, 0.85}));
  EXPECT_FALSE(overlay.oi_contains({1.45, 0.0}));
}

TEST(GridOverlay, OiIsTheAnchorsComponent) {
  OccupancyMap map = walled_room(40, 30, 0.1, {0.0, 0.0});
  for (int iy = 0; iy < 30; ++iy) map.at(20, iy) = CellState::Occupied;  // two rooms
  const std::vector<Pose2> start{{1.0, 1.5, 0.0}};
  const GridOverlay west = make_grid_overlay(map, start, 1.0);
  const GridOverlay east = make_grid_overlay(map, start, 1.0, {1.5, 0.0});
  EXPECT_EQ(west.oi_count, 19 * 28);
  EXPECT_EQ(east.oi_count, 18 * 28);
  EXPECT_FALSE(west.oi_contains({1.5, 0.0}));
  EXPECT_TRUE(east.oi_contains({1.5, 0.0}));
}

TEST(GridOverlay, BadInputThrows) {
  const ShiftedRooms rooms;
  expect_error(
      [&] {
        make_grid_overlay(rooms.map, rooms.hypotheses, 1.0, {2.5, 0.0});
      },
      {"anchor", "(2.5", "not in a cell free in every"});
  expect_error([&] { make_grid_overlay(rooms.map, {}, 1.0); }, {"no hypotheses"});
  expect_error([&] { make_grid_overlay(rooms.map, rooms.hypotheses, 0.0); }, {"range"});
  expect_error([&] { make_grid_overlay(rooms.map, rooms.hypotheses, std::nan("")); }, {"range"});
  expect_error([&] { make_grid_overlay(OccupancyMap{}, rooms.hypotheses, 1.0); }, {"empty"});
  expect_error(
      [&] {
        make_grid_overlay(rooms.map, {{std::nan(""), 0.0, 0.0}}, 1.0);
      },
      {"hypothesis 0"});
  const std::vector<Pose2> apart{{2.0, 1.5, 0.0}, {20.0, 1.5, 0.0}};  // no common ground
  expect_error([&] { make_grid_overlay(rooms.map, apart, 1.0); }, {"anchor"});
}

TEST(SampleOverlayCells, PointsLieInTheirSetAndRepeatForASeed) {
  const ShiftedRooms rooms;
  const GridOverlay overlay = make_grid_overlay(rooms.map, rooms.hypotheses, 0.55);
  for (const bool useful : {false, true}) {
    Rng rng(7), again(7);
    const std::vector<Eigen::Vector2d> points = sample_overlay_cells(overlay, useful, 400, rng);
    ASSERT_EQ(points.size(), 400u);
    EXPECT_EQ(points, sample_overlay_cells(overlay, useful, 400, again));
    const std::vector<std::uint8_t>& set = useful ? overlay.useful : overlay.in_oi;
    for (const Eigen::Vector2d& p : points) {
      const Cell c = overlay.cell_of(p);
      ASSERT_TRUE(overlay.grid.contains(c.ix, c.iy));
      EXPECT_TRUE(set[overlay.grid.index(c.ix, c.iy)]) << p.transpose();
    }
  }
}

TEST(SampleOverlayCells, SpreadsOverTheWholeSet) {
  const ShiftedRooms rooms;
  const GridOverlay overlay = make_grid_overlay(rooms.map, rooms.hypotheses, 0.55);
  Rng rng(3);
  int west = 0;
  const int count = 4000;
  for (const Eigen::Vector2d& p : sample_overlay_cells(overlay, true, count, rng)) {
    west += p.x() < -0.5 ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(west) / count, 0.5, 0.05);  // U has equal halves
}

TEST(SampleOverlayCells, EmptySetOrCountGivesNoPoints) {
  const OccupancyMap map = walled_room(30, 30, 0.1, {0.0, 0.0});
  const GridOverlay overlay = make_grid_overlay(map, {{1.5, 1.5, 0.0}}, 1.0);
  Rng rng(1);
  EXPECT_TRUE(sample_overlay_cells(overlay, true, 10, rng).empty());  // U is empty
  EXPECT_TRUE(sample_overlay_cells(overlay, false, 0, rng).empty());
  expect_error([&] { sample_overlay_cells(overlay, false, -1, rng); }, {"count", "-1"});
}

}  // namespace
}  // namespace gridloc
