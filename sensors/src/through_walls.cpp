// Returns whose beam crosses a wall of the map (through_walls.hpp).
#include "gridloc/sensors/through_walls.hpp"

#include <cmath>

#include "gridloc/grids/cell_walk.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// Whether the beam from `from` (grid frame, m) along `direction` crosses an Occupied cell
/// of `map` before `length` m.
bool crosses_a_wall(const OccupancyMap& map, const Eigen::Vector2d& from,
                    const Eigen::Vector2d& direction, double length) {
  const double res = map.geometry.resolution;
  CellWalk walk(from.x() / res, from.y() / res, direction.x(), direction.y());
  const double cells = length / res;  // the walk's parameter is in cells along a unit direction
  while (walk.t < cells) {
    if (map.geometry.contains(walk.ix, walk.iy) &&
        map.at(walk.ix, walk.iy) == CellState::Occupied) {
      return true;
    }
    walk.step();
  }
  return false;
}

}  // namespace

ThroughWalls through_walls(const OccupancyMap& map, const RangeScan& scan, const Pose2& pose,
                           double margin_m) {
  if (!(margin_m >= 0.0) || !std::isfinite(margin_m)) {
    throw Error("through_walls: margin_m must be finite and >= 0, got " + std::to_string(margin_m));
  }
  validate(scan);
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Eigen::Vector2d sensor(local.x, local.y);
  ThroughWalls result;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double range = scan.ranges[k];
    if (!(range < scan.max_range)) continue;  // no return
    ++result.returns;
    const double angle = local.theta + scan.angles[k];
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    if (range > margin_m && crosses_a_wall(map, sensor, direction, range - margin_m)) {
      ++result.through;
    }
  }
  return result;
}

}  // namespace gridloc
