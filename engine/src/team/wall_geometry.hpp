#pragma once
// Plane geometry on a map's walls for team localization: distances, crossings, ray casts.
#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "gridloc/engine/team/map_features.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc::team_detail {

inline double heading_of(const Eigen::Vector2d& v) {
  return std::atan2(v.y(), v.x());
}

inline Eigen::Vector2d unit_at(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

inline Eigen::Vector2d wall_direction(const MapWall& wall) {
  return (wall.b - wall.a).normalized();
}

/// Whether the open segments p-q and a-b cross or touch (p, q strictly inside the test).
bool segments_meet(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b);

/// Distance along the unit direction from origin to the first wall, or +infinity.
double ray_distance(const MapFeatures& map, const Eigen::Vector2d& origin,
                    const Eigen::Vector2d& direction);

/// Whether p lies in the free space the walls enclose (the walls have it on their left; the
/// even-odd rule along a ray).
bool inside_free_space(const MapFeatures& map, const Eigen::Vector2d& p);

}  // namespace gridloc::team_detail
