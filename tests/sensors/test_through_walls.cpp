// Tests of through_walls: a scan at its true pose sees no wall of the map between the sensor
// and its returns; the same scan at a wrong place shoots beams through walls.
#include "gridloc/sensors/through_walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/grids/error.hpp"
#include "walled_room.hpp"

namespace gridloc {
namespace {

OccupancyMap room(bool inner_wall) {
  return test::walled_room(inner_wall);
}

/// Four beams (east, north, west, south) with the given ranges; 8 m is no return.
RangeScan four_beams(double east, double north, double west, double south) {
  RangeScan scan;
  scan.max_range = 8.0;
  scan.angles = {0.0, 0.5 * std::numbers::pi, std::numbers::pi, 1.5 * std::numbers::pi};
  scan.ranges = {east, north, west, south};
  return scan;
}

TEST(ThroughWalls, AScanAtItsPoseSeesNoWallBeforeItsReturns) {
  // From the room's centre (3, 3) every wall's inner face is 1.95 m away.
  const RangeScan scan = four_beams(1.95, 1.95, 1.95, 1.95);
  const ThroughWalls at_truth = through_walls(room(false), scan, {3.0, 3.0, 0.0}, 0.3);
  EXPECT_EQ(at_truth.returns, 4);
  EXPECT_EQ(at_truth.through, 0);
  EXPECT_DOUBLE_EQ(at_truth.share(), 0.0);
}

TEST(ThroughWalls, TheSameScanAtAWrongPlaceCrossesWalls) {
  const RangeScan scan = four_beams(1.95, 1.95, 1.95, 1.95);
  // 1 m east: the east beam crosses the east wall 1 m before its return; turned by a half
  // turn the beams swap and nothing crosses.
  const ThroughWalls shifted = through_walls(room(false), scan, {4.0, 3.0, 0.0}, 0.3);
  EXPECT_EQ(shifted.through, 1);
  EXPECT_DOUBLE_EQ(shifted.share(), 0.25);
  EXPECT_EQ(through_walls(room(false), scan, {3.0, 3.0, std::numbers::pi}, 0.3).through, 0);
  // From (2, 3) with the west wall 0.95 m away: a wall the scan did not see (x = 3 m, below
  // y = 3.5 m) lies between the sensor and the east return.
  const RangeScan west_near = four_beams(1.95, 1.95, 0.95, 1.95);
  EXPECT_EQ(through_walls(room(false), west_near, {2.0, 3.0, 0.0}, 0.3).through, 0);
  const ThroughWalls inner = through_walls(room(true), west_near, {2.0, 3.0, 0.0}, 0.3);
  EXPECT_EQ(inner.through, 1);  // east, through the inner wall 1 m away
}

TEST(ThroughWalls, TheMarginAndBeamsWithoutAReturn) {
  // The east return 0.2 m past the east wall: within a 0.3 m margin it is the wall's own.
  const RangeScan past = four_beams(2.15, 1.95, 1.95, 8.0);
  const ThroughWalls within = through_walls(room(false), past, {3.0, 3.0, 0.0}, 0.3);
  EXPECT_EQ(within.returns, 3);  // the south beam has no return
  EXPECT_EQ(within.through, 0);
  EXPECT_EQ(through_walls(room(false), past, {3.0, 3.0, 0.0}, 0.1).through, 1);
  EXPECT_DOUBLE_EQ(ThroughWalls{}.share(), 0.0);
}

TEST(ThroughWalls, BadInputsAreNamed) {
  const RangeScan scan = four_beams(1.0, 1.0, 1.0, 1.0);
  EXPECT_THROW(through_walls(room(false), scan, {3.0, 3.0, 0.0}, -0.1), Error);
  EXPECT_THROW(through_walls(room(false), scan, {3.0, 3.0, 0.0}, std::nan("")), Error);
  RangeScan bad = scan;
  bad.ranges[0] = std::nan("");
  EXPECT_THROW(through_walls(room(false), bad, {3.0, 3.0, 0.0}, 0.3), Error);
}

}  // namespace
}  // namespace gridloc
