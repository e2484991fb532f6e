#pragma once
// A small walled room for tests of what a scan sees through walls.
#include "gridloc/grids/grid.hpp"

namespace gridloc::test {

/// A 4 m x 4 m room of 5 cm cells, walls one cell thick on its border, its corner at (1, 1)
/// in the world; with `inner_wall` a wall along x = 3 m (world) from y = 1 to 3.5 m.
inline OccupancyMap walled_room(bool inner_wall = false) {
  GridGeometry geometry;
  geometry.resolution = 0.05;
  geometry.origin = {1.0, 1.0};
  geometry.width = geometry.height = 80;
  OccupancyMap map(geometry, CellState::Free);
  for (int k = 0; k < 80; ++k) {
    map.at(k, 0) = map.at(k, 79) = map.at(0, k) = map.at(79, k) = CellState::Occupied;
  }
  if (inner_wall) {
    for (int iy = 0; iy < 50; ++iy) map.at(40, iy) = CellState::Occupied;
  }
  return map;
}

}  // namespace gridloc::test
