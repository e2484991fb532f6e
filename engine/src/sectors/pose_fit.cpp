// The pose geometry of the sectors' localization: located vertices, rigid and trimmed fits,
// the Gauss-Newton polish on the map's walls and its covariance.
#include "pose_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gridloc/grids/planar.hpp"

namespace gridloc::sectors_detail {
namespace {

/// The Gauss-Newton normal equations of the scan's points (robot frame) at `pose` against
/// their nearest wall within `gate` (m): H, the gradient g, the sum of squared distances and
/// the points used.
struct NormalEquations {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double sum2 = 0.0;
  int used = 0;
};

NormalEquations normal_equations(const std::vector<Eigen::Vector2d>& points,
                                 const std::vector<Wall>& walls, const Pose2& pose, double gate) {
  NormalEquations equations;
  const Eigen::Rotation2Dd R(pose.theta);
  const Eigen::Vector2d t(pose.x, pose.y);
  for (const auto& p : points) {
    const Eigen::Vector2d rp = R * p, w = rp + t;
    double best = gate, r = 0.0;
    const Wall* nearest = nullptr;
    for (const Wall& wall : walls) {
      const double u = (w - wall.a).dot(wall.e) * wall.inv_len2;
      if (u < 0.0 || u > 1.0) continue;
      const double d = wall.normal.dot(w - wall.a);
      if (std::abs(d) < best) best = std::abs(d), r = d, nearest = &wall;
    }
    if (nearest == nullptr) continue;
    const Eigen::Vector2d& n = nearest->normal;
    const Eigen::Vector3d J(n.x(), n.y(), n.dot(Eigen::Vector2d(-rp.y(), rp.x())));
    equations.H += J * J.transpose();
    equations.g += J * r;
    equations.sum2 += r * r;
    ++equations.used;
  }
  return equations;
}

}  // namespace

/// The vertex at an M reading: the intersection of the lines fitted to `k` readings on each
/// side (seed 000 eqs. (6)-(9)), or the reading itself when they are near parallel.
Eigen::Vector2d locate_vertex(const std::vector<Eigen::Vector2d>& points, int beam,
                              int line_points) {
  const int n = static_cast<int>(points.size());
  const auto point = [&](int i) { return points[((i % n) + n) % n]; };
  // The line through `line_points` readings on one side (dir +1 or -1): centre, direction.
  const auto fit = [&](int dir, Eigen::Vector2d& centre, Eigen::Vector2d& direction) {
    const FittedLine line = total_least_squares_line(
        static_cast<std::size_t>(line_points),
        [&](std::size_t k) { return point(beam + dir * (static_cast<int>(k) + 1)); });
    centre = line.centroid;
    direction = line.direction;
  };
  Eigen::Vector2d c1, d1, c2, d2;
  fit(+1, c1, d1);
  fit(-1, c2, d2);
  if (std::abs(cross(d1, d2)) < 0.05) return point(beam);  // < 3 deg apart: no corner
  const Eigen::Vector2d v = line_intersection(c1, d1, c2, d2);
  // A corner far from its reading is a bad fit (another surface in the window).
  return (v - point(beam)).norm() < 0.3 + 0.05 * point(beam).norm() ? v : point(beam);
}

/// Rigid fit: the pose (R, t) with world = R * local + t, least squares.
Pose2 rigid_fit(const std::vector<Eigen::Vector2d>& local,
                const std::vector<Eigen::Vector2d>& world) {
  Eigen::Vector2d local_centre = Eigen::Vector2d::Zero(), world_centre = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < local.size(); ++k) local_centre += local[k], world_centre += world[k];
  local_centre /= static_cast<double>(local.size());
  world_centre /= static_cast<double>(world.size());
  double s = 0.0, c = 0.0;
  for (std::size_t k = 0; k < local.size(); ++k) {
    const Eigen::Vector2d a = local[k] - local_centre, b = world[k] - world_centre;
    c += a.dot(b);
    s += a.x() * b.y() - a.y() * b.x();
  }
  const double theta = std::atan2(s, c);
  const Eigen::Vector2d t = world_centre - Eigen::Rotation2Dd(theta) * local_centre;
  return {t.x(), t.y(), theta};
}

std::vector<Wall> walls_of(const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& edges) {
  std::vector<Wall> out;
  for (const auto& [a, b] : edges) {
    const Eigen::Vector2d e = b - a;
    out.push_back({a, e, Eigen::Vector2d(-e.y(), e.x()).normalized(), 1.0 / e.squaredNorm()});
  }
  return out;
}

/// Gauss-Newton on the distances from the scan's points (robot frame) to their nearest map
/// wall, with a shrinking gate: a pose from a few located vertices, made exact by every
/// reading on the walls it explains.
Pose2 polish(const std::vector<Eigen::Vector2d>& points, const std::vector<Wall>& walls,
             Pose2 pose) {
  for (const double gate : {0.3, 0.15, 0.08, 0.04, 0.04}) {
    const NormalEquations equations = normal_equations(points, walls, pose, gate);
    if (equations.used < 3) break;
    const Eigen::Vector3d step = equations.H.ldlt().solve(-equations.g);
    if (!step.allFinite()) break;
    pose = {pose.x + step.x(), pose.y + step.y(), normalize_angle(pose.theta + step.z())};
  }
  return pose;
}

/// The Gauss-Newton covariance sigma^2 H^-1 of a pose fitted to the walls (polish()'s last
/// gate): sigma^2 from the residuals, infinite variances where the walls leave a direction
/// free (a corridor's axis).
Eigen::Matrix3d pose_covariance(const std::vector<Eigen::Vector2d>& points,
                                const std::vector<Wall>& walls, const Pose2& pose) {
  const NormalEquations equations = normal_equations(points, walls, pose, 0.04);
  const Eigen::Matrix3d& H = equations.H;
  const int used = equations.used;
  const double sum2 = equations.sum2;
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Constant(inf);
  if (used <= 3) return cov;
  // A floor on sigma: exact (noise-free) readings would claim an exact pose.
  const double sigma2 = std::max(sum2 / (used - 3), 1e-6);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
  if (eig.eigenvalues().minCoeff() < 1e-9 * std::max(1.0, eig.eigenvalues().maxCoeff())) {
    return cov;
  }
  return sigma2 * H.inverse();
}

/// Located vertices that a rigid motion cannot put near their map vertices are wrong
/// correspondences (a corner fitted across two surfaces) or a wrong match: cheap to rule out
/// before the residual. A D reading lies within a beam step of its corner, so the allowance
/// (m) grows with range.
double allowance(double beam_step, const Eigen::Vector2d& local) {
  return 0.3 + 1.5 * beam_step * local.norm();
}

/// The rigid fit with correspondences it cannot place left out, worst first (`local` keeps
/// the rest); nullopt when fewer than two remain.
std::optional<Pose2> trimmed_fit(std::vector<Eigen::Vector2d>& local,
                                 std::vector<Eigen::Vector2d> world, double beam_step) {
  while (local.size() >= 2) {
    const Pose2 pose = rigid_fit(local, world);
    const Eigen::Rotation2Dd R(pose.theta);
    const Eigen::Vector2d t(pose.x, pose.y);
    std::size_t worst = 0;
    double worst_excess = 0.0;
    for (std::size_t k = 0; k < local.size(); ++k) {
      const double excess = (R * local[k] + t - world[k]).norm() - allowance(beam_step, local[k]);
      if (excess > worst_excess) worst_excess = excess, worst = k;
    }
    if (worst_excess <= 0.0) return pose;
    local.erase(local.begin() + static_cast<std::ptrdiff_t>(worst));
    world.erase(world.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  return std::nullopt;
}

}  // namespace gridloc::sectors_detail
