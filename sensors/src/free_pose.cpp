// Free poses on a map for a robot's footprint (free_pose.hpp).
#include "gridloc/sensors/free_pose.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc {
namespace {

/// True when robot-frame point p is inside the footprint or within `clearance` of it.
bool near_footprint(const Footprint& footprint, const Eigen::Vector2d& p, double clearance) {
  if (footprint.polygon.size() < 3) return p.norm() <= clearance;
  if (footprint_contains(footprint, p)) return true;
  const std::vector<Eigen::Vector2d>& polygon = footprint.polygon;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    if (distance_to_segment(p, polygon[j], polygon[i]) <= clearance) return true;
  }
  return false;
}

/// True when the footprint at grid-frame `pose`, grown by `clearance`, covers only free cells
/// of the (2 reach + 1)^2 cells around it.
bool footprint_clear(const OccupancyMap& map, const Footprint& footprint, const Pose2& pose,
                     int reach, double clearance) {
  const GridGeometry& geometry = map.geometry;
  const Cell center = geometry.cell_of(pose.x, pose.y);
  const double cs = std::cos(pose.theta), sn = std::sin(pose.theta);
  for (int iy = center.iy - reach; iy <= center.iy + reach; ++iy) {
    for (int ix = center.ix - reach; ix <= center.ix + reach; ++ix) {
      if (geometry.contains(ix, iy) && map.at(ix, iy) == CellState::Free) continue;
      const Eigen::Vector2d w = geometry.cell_center(ix, iy) - Eigen::Vector2d(pose.x, pose.y);
      const Eigen::Vector2d p(cs * w.x() + sn * w.y(), -sn * w.x() + cs * w.y());
      if (near_footprint(footprint, p, clearance + 0.5 * geometry.resolution)) return false;
    }
  }
  return true;
}

/// The cells around a pose that footprint_clear must look at.
int footprint_reach(const OccupancyMap& map, const SonarRing& ring, double clearance) {
  double radius = clearance;
  for (const auto& p : ring.footprint.polygon) radius = std::max(radius, p.norm() + clearance);
  return static_cast<int>(std::ceil(radius / map.geometry.resolution)) + 1;
}

}  // namespace

bool pose_is_free(const OccupancyMap& map, const SonarRing& ring, const Pose2& pose,
                  double clearance) {
  return footprint_clear(map, ring.footprint, map.geometry.to_grid_frame(pose),
                         footprint_reach(map, ring, clearance), clearance);
}

Pose2 sample_free_pose(const OccupancyMap& map, const SonarRing& ring, double clearance, Rng& rng) {
  const GridGeometry& geometry = map.geometry;
  const int reach = footprint_reach(map, ring, clearance);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Pose2 local{rng.uniform(0.0, geometry.width * geometry.resolution),
                      rng.uniform(0.0, geometry.height * geometry.resolution),
                      rng.uniform(-std::numbers::pi, std::numbers::pi)};
    if (footprint_clear(map, ring.footprint, local, reach, clearance)) {
      return geometry.to_world_frame(local);
    }
  }
  throw Error("sample_free_pose: found no free pose with the requested clearance on this map");
}

}  // namespace gridloc
