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
  double nearest = std::numeric_limits<double>::infinity();
  for (const MapWall& wall : map.walls) {
    const Eigen::Vector2d s = wall.b - wall.a;
    const double denominator = cross(direction, s);
    if (std::abs(denominator) < 1e-15) continue;
    const double t = cross(wall.a - origin, s) / denominator;
    const double u = cross(wall.a - origin, direction) / denominator;
    if (t >= 0.0 && u >= -1e-12 && u <= 1.0 + 1e-12) nearest = std::min(nearest, t);
  }
  return nearest;
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
