#pragma once
// Shared by the laser drive tests: a corridor whose doors repeat (one scan of a 180-degree
// laser cannot tell two places apart) and front-laser scans simulated in it.
#include <cmath>
#include <numbers>

#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/scan_sim.hpp"

namespace gridloc::test {

/// A 20 m x 2 m corridor at 5 cm (walls one cell thick, free inside, unknown outside) with
/// doors into 1 m deep alcoves: 1 m wide on the north wall at x = 4 m and x = 12 m, 1.6 m
/// wide on the south wall at x = 9.3 m (a door of its own width: no place turned by 180
/// degrees sees it as a north door). Seen from (2.5, 2.5) and (10.5, 2.5) facing +x within
/// 3 m, the two places look the same; a drive from x = 8.5, past the south door, tells them
/// apart.
inline OccupancyMap door_corridor() {
  const double res = 0.05;
  GridGeometry geometry;
  geometry.resolution = res;
  geometry.width = 400;
  geometry.height = 100;  // y from 0 to 5 m; the corridor spans y in [1.5, 3.5]
  OccupancyMap map(geometry, CellState::Unknown);
  const auto cell = [res](double v) { return static_cast<int>(std::floor(v / res)); };
  const auto fill = [&](double x0, double x1, double y0, double y1, CellState state) {
    for (int iy = cell(y0); iy <= cell(y1 - 1e-9); ++iy)
      for (int ix = cell(x0); ix <= cell(x1 - 1e-9); ++ix) map.at(ix, iy) = state;
  };
  fill(0.0, 20.0, 1.45, 3.55, CellState::Occupied);
  fill(0.05, 19.95, 1.5, 3.5, CellState::Free);
  for (double door : {4.0, 12.0}) {  // north alcoves
    fill(door - 0.55, door + 0.55, 3.5, 4.55, CellState::Occupied);
    fill(door - 0.5, door + 0.5, 3.5, 4.5, CellState::Free);
  }
  fill(8.45, 10.15, 0.45, 1.5, CellState::Occupied);  // the south alcove
  fill(8.5, 10.1, 0.5, 1.5, CellState::Free);
  return map;
}

/// A 181-beam front laser (-90..90 degrees) of range `max_range` at `pose`, noise-free.
inline RangeScan front_scan(const OccupancyMap& map, const Pose2& pose, double max_range) {
  const RangeScan all = simulate_scan(map, pose, 360, max_range, 0.0, 1);
  RangeScan front;
  front.max_range = max_range;
  for (std::size_t k = 0; k < all.angles.size(); ++k) {
    if (std::abs(all.angles[k]) <= 0.5 * std::numbers::pi + 1e-9) {
      front.angles.push_back(all.angles[k]);
      front.ranges.push_back(all.ranges[k]);
    }
  }
  return front;
}

/// Two identical 4 m x 3 m rooms (x in [1, 5] and [7, 11], y in [4, 7]) with the same box
/// in each, opening through a 1 m door in the south wall onto a corridor (y in [2, 3.95])
/// from x = 0.5 to x = 15: the corridor's ends are what tell the rooms apart.
inline OccupancyMap two_rooms() {
  const double res = 0.05;
  GridGeometry geometry;
  geometry.resolution = res;
  geometry.width = 320;
  geometry.height = 160;
  OccupancyMap map(geometry, CellState::Unknown);
  const auto cell = [res](double v) { return static_cast<int>(std::lround(v / res)); };
  const auto fill = [&](double x0, double x1, double y0, double y1, CellState state) {
    for (int iy = cell(y0); iy < cell(y1); ++iy)
      for (int ix = cell(x0); ix < cell(x1); ++ix) map.at(ix, iy) = state;
  };
  fill(0.45, 15.05, 1.95, 4.0, CellState::Occupied);  // the corridor's walls
  fill(0.5, 15.0, 2.0, 3.95, CellState::Free);
  for (double left : {1.0, 7.0}) {
    fill(left - 0.05, left + 4.05, 3.95, 7.05, CellState::Occupied);
    fill(left, left + 4.0, 4.0, 7.0, CellState::Free);
    fill(left + 2.5, left + 3.5, 3.95, 4.0, CellState::Free);     // the door
    fill(left + 0.5, left + 1.0, 6.0, 6.5, CellState::Occupied);  // the box
  }
  return map;
}

}  // namespace gridloc::test
