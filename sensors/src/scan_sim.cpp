#include "gridloc/sensors/scan_sim.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "gridloc/grids/cell_walk.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

/// Distance (m) from grid-frame point (gx, gy) along direction a to the first Occupied cell
/// (Amanatides-Woo traversal, so no cell is skipped), or max_range.
double cast(const OccupancyMap& map, double gx, double gy, double a, double max_range) {
  const GridGeometry& g = map.geometry;
  const double res = g.resolution;
  CellWalk walk(gx / res, gy / res, std::cos(a), std::sin(a));  // in cells
  const double limit = max_range / res;
  while (walk.t < limit) {
    if (!g.contains(walk.ix, walk.iy)) return max_range;
    if (map.at(walk.ix, walk.iy) == CellState::Occupied) return walk.t * res;
    walk.step();
  }
  return max_range;
}

}  // namespace

RangeScan simulate_scan(const OccupancyMap& map, const Pose2& pose, int beams, double max_range,
                        double sigma_m, std::uint64_t seed) {
  if (beams < 1) {
    throw Error("simulate_scan: beams must be >= 1, got " + std::to_string(beams));
  }
  if (!(max_range > 0.0) || !std::isfinite(max_range)) {
    throw Error("simulate_scan: max_range must be positive and finite, got " +
                std::to_string(max_range));
  }
  if (!(sigma_m >= 0.0) || !std::isfinite(sigma_m)) {  // also NaN
    throw Error("simulate_scan: sigma_m must be finite and >= 0, got " + std::to_string(sigma_m));
  }
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw Error("simulate_scan: pose must be finite, got (" + std::to_string(pose.x) + ", " +
                std::to_string(pose.y) + ", " + std::to_string(pose.theta) + ")");
  }
  const Pose2 p = map.geometry.to_grid_frame(pose);
  Rng rng(seed);
  RangeScan scan;
  scan.max_range = max_range;
  scan.angles.reserve(static_cast<std::size_t>(beams));
  scan.ranges.reserve(static_cast<std::size_t>(beams));
  for (int k = 0; k < beams; ++k) {
    const double angle = -std::numbers::pi + 2.0 * std::numbers::pi * k / beams;
    double r = cast(map, p.x, p.y, p.theta + angle, max_range);
    if (r < max_range) r = std::clamp(r + sigma_m * rng.gaussian(), 0.0, max_range);
    scan.angles.push_back(angle);
    scan.ranges.push_back(r);
  }
  return scan;
}

}  // namespace gridloc
