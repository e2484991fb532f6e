#pragma once
// The pose geometry of the sectors' localization (internal): vertices located in a scan, rigid
// fits to map vertices, and the Gauss-Newton polish and covariance on the map's walls.
#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

#include "gridloc/grids/geometry.hpp"

namespace gridloc::sectors_detail {

/// The vertex at an M reading, from the lines fitted to `line_points` readings on each side.
Eigen::Vector2d locate_vertex(const std::vector<Eigen::Vector2d>& points, int beam,
                              int line_points);

/// Rigid fit: the pose (R, t) with world = R * local + t, least squares.
Pose2 rigid_fit(const std::vector<Eigen::Vector2d>& local,
                const std::vector<Eigen::Vector2d>& world);

/// A map edge ready for point-to-wall distances: its start, direction, 1 / length^2 and unit
/// normal, computed once per localization rather than per point and pass.
struct Wall {
  Eigen::Vector2d a, e, normal;
  double inv_len2;
};

/// The walls of the map's edges.
std::vector<Wall> walls_of(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& edges);

/// Gauss-Newton on the point-to-wall distances, with a shrinking gate: `pose` made exact.
Pose2 polish(const std::vector<Eigen::Vector2d>& points, const std::vector<Wall>& walls,
             Pose2 pose);

/// The Gauss-Newton covariance of a pose fitted to the walls (infinite where they leave it free).
Eigen::Matrix3d pose_covariance(const std::vector<Eigen::Vector2d>& points,
                                const std::vector<Wall>& walls, const Pose2& pose);

/// How far (m) a located vertex may lie from its map vertex: grows with range.
double allowance(double beam_step, const Eigen::Vector2d& local);

/// The rigid fit with the correspondences it cannot place left out; nullopt below two.
std::optional<Pose2> trimmed_fit(std::vector<Eigen::Vector2d>& local,
                                 std::vector<Eigen::Vector2d> world, double beam_step);

}  // namespace gridloc::sectors_detail
