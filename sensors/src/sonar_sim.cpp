#include "gridloc/sensors/sonar_sim.hpp"

#include <cmath>
#include <limits>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

bool occupied(const OccupancyMap& map, int ix, int iy) {
  return map.at(ix, iy) == CellState::Occupied;
}

/// Outward normal of the obstacle surface at an occupied cell: the mean direction from the
/// cell to its non-occupied neighbours (5x5 window).
Eigen::Vector2d surface_normal(const OccupancyMap& map, int ix, int iy) {
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const int nx = ix + dx, ny = iy + dy;
      if ((dx || dy) && map.geometry.contains(nx, ny) && !occupied(map, nx, ny)) {
        normal += Eigen::Vector2d(dx, dy).normalized();
      }
    }
  }
  return normal.norm() > 1e-9 ? normal.normalized() : normal;
}

/// Distance along a ray from (x, y) (grid frame) in direction (ux, uy) to the first occupied
/// cell (Amanatides-Woo traversal); +inf when none within max_range or the ray leaves the map.
/// On a hit, `hit` receives the cell.
double trace(const OccupancyMap& map, double x, double y, double ux, double uy, double max_range,
             Cell& hit) {
  const double res = map.geometry.resolution;
  Cell c = map.geometry.cell_of(x, y);
  const int step_x = ux > 0 ? 1 : -1, step_y = uy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double dt_x = ux != 0 ? res / std::abs(ux) : inf;
  const double dt_y = uy != 0 ? res / std::abs(uy) : inf;
  double t_x = ux != 0 ? ((c.ix + (ux > 0)) * res - x) / ux : inf;
  double t_y = uy != 0 ? ((c.iy + (uy > 0)) * res - y) / uy : inf;
  double t = 0.0;
  while (t <= max_range) {
    if (!map.geometry.contains(c.ix, c.iy)) return inf;
    if (occupied(map, c.ix, c.iy)) {
      hit = c;
      return t;
    }
    if (t_x < t_y) {
      t = t_x;
      t_x += dt_x;
      c.ix += step_x;
    } else {
      t = t_y;
      t_y += dt_y;
      c.iy += step_y;
    }
  }
  return inf;
}

/// Throws gridloc::Error for a pose that is not finite or options out of range.
void check_simulation(const SonarSimOptions& options, const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw Error("simulate: pose must be finite");
  }
  for (double probability : {options.dropout_prob, options.crosstalk_prob}) {
    if (!(probability >= 0.0 && probability <= 1.0)) {
      throw Error("simulate: probabilities must lie in [0, 1]");
    }
  }
  if (!(options.range_sigma_m >= 0.0) || !(options.range_sigma_frac >= 0.0)) {
    throw Error("simulate: noise sigmas must be >= 0");
  }
  if (!(options.ray_step_deg > 0.0)) throw Error("simulate: ray_step_deg must be positive");
}

/// The shortest echo of `sonar` at robot pose `grid_pose` (grid frame): the nearest hit of
/// the rays fanned across its cone, a hit seen beyond the specular incidence excepted; +inf
/// when none.
double nearest_echo(const OccupancyMap& map, const SonarSpec& sonar, const Pose2& grid_pose,
                    const SonarSimOptions& options, double cos_specular) {
  const double sx = grid_pose.x + sonar.radius * std::cos(sonar.bearing + grid_pose.theta);
  const double sy = grid_pose.y + sonar.radius * std::sin(sonar.bearing + grid_pose.theta);
  const double axis = sonar.heading + grid_pose.theta;
  const int rays =
      std::max(2, static_cast<int>(std::ceil(rad2deg(sonar.cone) / options.ray_step_deg)) + 1);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < rays; ++k) {
    const double angle = axis - 0.5 * sonar.cone + sonar.cone * k / (rays - 1);
    const double ux = std::cos(angle), uy = std::sin(angle);
    Cell hit;
    const double t = trace(map, sx, sy, ux, uy, sonar.max_range, hit);
    if (!(t < best)) continue;
    if (options.specular_incidence_deg < 90.0) {
      const Eigen::Vector2d normal = surface_normal(map, hit.ix, hit.iy);
      // cos(incidence) = -ray . normal; a smooth surface seen too obliquely stays silent.
      if (normal.norm() > 0.0 && -(ux * normal.x() + uy * normal.y()) < cos_specular) continue;
    }
    best = t;
  }
  return best;
}

/// The reading of `sonar` for its nearest echo `best`: range noise, crosstalk (a wrong short
/// echo), dropout, within [min_range, max_range].
double noisy_range(const SonarSpec& sonar, double best, const SonarSimOptions& options, Rng& rng) {
  // Draw every random number whatever happens, so one option never shifts another's stream.
  const double u_drop = rng.uniform(), u_cross = rng.uniform(), u_short = rng.uniform();
  const double noise = rng.gaussian();
  double range = best;
  if (std::isfinite(range)) {
    range += noise * (options.range_sigma_m + options.range_sigma_frac * range);
  }
  if (u_cross < options.crosstalk_prob) {
    const double upper = std::isfinite(best) ? std::min(best, sonar.max_range) : sonar.max_range;
    range = sonar.min_range + u_short * (upper - sonar.min_range);
  }
  if (u_drop < options.dropout_prob) range = sonar.max_range;
  if (!std::isfinite(range) || range >= sonar.max_range) range = sonar.max_range;
  return std::max(range, sonar.min_range);
}

}  // namespace

SonarSimOptions SonarSimOptions::realistic(std::uint64_t seed) {
  SonarSimOptions options;
  options.seed = seed;
  options.range_sigma_m = 0.02;
  options.range_sigma_frac = 0.01;
  options.dropout_prob = 0.02;
  options.specular_incidence_deg = 75.0;
  options.crosstalk_prob = 0.01;
  return options;
}

SonarSimOptions SonarSimOptions::harsh(std::uint64_t seed) {
  SonarSimOptions options;
  options.seed = seed;
  options.range_sigma_m = 0.03;
  options.range_sigma_frac = 0.02;
  options.dropout_prob = 0.05;
  options.specular_incidence_deg = 60.0;
  options.crosstalk_prob = 0.05;
  return options;
}

std::vector<double> simulate_sonar(const OccupancyMap& map, const SonarRing& ring,
                                   const Pose2& pose, const SonarSimOptions& options) {
  check_simulation(options, pose);
  const Pose2 grid_pose = map.geometry.to_grid_frame(pose);
  const Cell robot = map.geometry.cell_of(grid_pose.x, grid_pose.y);
  if (!map.geometry.contains(robot.ix, robot.iy)) {
    throw Error("simulate: pose (" + std::to_string(pose.x) + ", " + std::to_string(pose.y) +
                ") lies outside the map");
  }
  const double cos_specular = std::cos(deg2rad(options.specular_incidence_deg));
  Rng rng(options.seed);
  std::vector<double> ranges;
  ranges.reserve(ring.sonars.size());
  for (const SonarSpec& sonar : ring.sonars) {
    const double best = nearest_echo(map, sonar, grid_pose, options, cos_specular);
    ranges.push_back(noisy_range(sonar, best, options, rng));
  }
  return ranges;
}

}  // namespace gridloc
