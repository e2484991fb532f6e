#include "wall_geometry.hpp"

#include <algorithm>

namespace gridloc::team_detail {

bool segments_meet(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b) {
  const Eigen::Vector2d r = q - p, s = b - a;
  const double denominator = cross(r, s);
  if (std::abs(denominator) < 1e-15) {  // parallel: meet only when collinear and overlapping
    if (std::abs(cross(a - p, r)) > 1e-12 * std::max(1.0, r.norm())) return false;
    const double length2 = r.squaredNorm();
    if (length2 == 0.0) return false;
    const double t0 = (a - p).dot(r) / length2, t1 = (b - p).dot(r) / length2;
    return std::max(t0, t1) >= 0.0 && std::min(t0, t1) <= 1.0;
  }
  const double t = cross(a - p, s) / denominator, u = cross(a - p, r) / denominator;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

double ray_distance(const MapFeatures& map, const Eigen::Vector2d& origin,
                    const Eigen::Vector2d& direction) {
  constexpr RayTolerances tolerances{.parallel = 1e-15, .slack = 1e-12, .origin_counts = true};
  return gridloc::ray_distance(origin, direction, map.walls, tolerances);
}

bool inside_free_space(const MapFeatures& map, const Eigen::Vector2d& p) {
  // A ray in a direction no axis-aligned map has, so it meets vertices only by chance.
  const Eigen::Vector2d far = p + 1e7 * Eigen::Vector2d(0.8191520443, 0.5735764364);
  int crossings = 0;
  for (const MapWall& wall : map.walls)
    if (segments_meet(p, far, wall.a, wall.b)) ++crossings;
  return crossings % 2 == 1;
}

}  // namespace gridloc::team_detail
