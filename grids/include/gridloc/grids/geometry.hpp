#pragma once
/// Poses and grid geometry. World frame: x east, y north, theta CCW from +x, metres and
/// radians. A grid's row index grows with world y; column index with world x.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace gridloc {

/// Normalizes an angle to (-pi, pi].
inline double normalize_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}
inline double deg2rad(double d) {
  return d * std::numbers::pi / 180.0;
}
inline double rad2deg(double r) {
  return r * 180.0 / std::numbers::pi;
}

/// A 2-D pose: position in metres, heading in radians.
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

/// The pose b in a's frame, a^-1 * b: where b lies as seen from a (odometry increments,
/// scan-pair motions).
inline Pose2 relative_pose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, normalize_angle(b.theta - a.theta)};
}

/// The pose b given in a's frame, in a's parent frame: a * b (the inverse of relative_pose).
inline Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, normalize_angle(a.theta + b.theta)};
}

/// Integer cell coordinates (column ix grows with x, row iy grows with y).
struct Cell {
  int ix = 0;
  int iy = 0;
  friend bool operator==(const Cell&, const Cell&) = default;
};

/// Where a grid lies in the world. `origin` is the world position of the lower-left corner
/// of cell (0,0); the grid is rotated by `yaw` about that corner (ROS map_server's origin yaw).
struct GridGeometry {
  double resolution = 0.1;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  int width = 0;
  int height = 0;

  bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::size_t index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(ix);
  }
  std::size_t size() const { return static_cast<std::size_t>(width) * height; }

  /// World pose -> pose in the grid frame (origin at the corner of cell (0,0), axes along
  /// columns and rows).
  Pose2 to_grid_frame(const Pose2& world) const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    const double dx = world.x - origin.x(), dy = world.y - origin.y();
    return {c * dx + s * dy, -s * dx + c * dy, normalize_angle(world.theta - yaw)};
  }
  /// Pose in the grid frame -> world pose.
  Pose2 to_world_frame(const Pose2& local) const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {origin.x() + c * local.x - s * local.y, origin.y() + s * local.x + c * local.y,
            normalize_angle(local.theta + yaw)};
  }
  /// The cell holding a point given in the grid frame (may lie outside the grid).
  Cell cell_of(double gx, double gy) const {
    return {static_cast<int>(std::floor(gx / resolution)),
            static_cast<int>(std::floor(gy / resolution))};
  }
  /// Centre of a cell in the grid frame.
  Eigen::Vector2d cell_center(int ix, int iy) const {
    return {(ix + 0.5) * resolution, (iy + 0.5) * resolution};
  }
};

}  // namespace gridloc
