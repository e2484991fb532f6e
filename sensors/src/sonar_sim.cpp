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
  Eigen::Vector2d n = Eigen::Vector2d::Zero();
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const int nx = ix + dx, ny = iy + dy;
      if ((dx || dy) && map.geometry.contains(nx, ny) && !occupied(map, nx, ny)) {
        n += Eigen::Vector2d(dx, dy).normalized();
      }
    }
  }
  return n.norm() > 1e-9 ? n.normalized() : n;
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

}  // namespace

SonarSimOptions SonarSimOptions::realistic(std::uint64_t seed) {
  SonarSimOptions o;
  o.seed = seed;
  o.range_sigma_m = 0.02;
  o.range_sigma_frac = 0.01;
  o.dropout_prob = 0.02;
  o.specular_incidence_deg = 75.0;
  o.crosstalk_prob = 0.01;
  return o;
}

SonarSimOptions SonarSimOptions::harsh(std::uint64_t seed) {
  SonarSimOptions o;
  o.seed = seed;
  o.range_sigma_m = 0.03;
  o.range_sigma_frac = 0.02;
  o.dropout_prob = 0.05;
  o.specular_incidence_deg = 60.0;
  o.crosstalk_prob = 0.05;
  return o;
}

std::vector<double> simulate_sonar(const OccupancyMap& map, const SonarRing& ring,
                                   const Pose2& pose, const SonarSimOptions& o) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw Error("simulate: pose must be finite");
  }
  for (double p : {o.dropout_prob, o.crosstalk_prob}) {
    if (!(p >= 0.0 && p <= 1.0)) throw Error("simulate: probabilities must lie in [0, 1]");
  }
  if (!(o.range_sigma_m >= 0.0) || !(o.range_sigma_frac >= 0.0)) {
    throw Error("simulate: noise sigmas must be >= 0");
  }
  if (!(o.ray_step_deg > 0.0)) throw Error("simulate: ray_step_deg must be positive");
  const Pose2 g = map.geometry.to_grid_frame(pose);
  const Cell robot = map.geometry.cell_of(g.x, g.y);
  if (!map.geometry.contains(robot.ix, robot.iy)) {
    throw Error("simulate: pose (" + std::to_string(pose.x) + ", " + std::to_string(pose.y) +
                ") lies outside the map");
  }
  const double cos_spec = std::cos(deg2rad(o.specular_incidence_deg));
  Rng rng(o.seed);
  std::vector<double> ranges;
  ranges.reserve(ring.sonars.size());
  for (const SonarSpec& s : ring.sonars) {
    const double sx = g.x + s.radius * std::cos(s.bearing + g.theta);
    const double sy = g.y + s.radius * std::sin(s.bearing + g.theta);
    const double axis = s.heading + g.theta;
    const int rays = std::max(2, static_cast<int>(std::ceil(rad2deg(s.cone) / o.ray_step_deg)) + 1);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < rays; ++k) {
      const double a = axis - 0.5 * s.cone + s.cone * k / (rays - 1);
      const double ux = std::cos(a), uy = std::sin(a);
      Cell hit;
      const double t = trace(map, sx, sy, ux, uy, s.max_range, hit);
      if (!(t < best)) continue;
      if (o.specular_incidence_deg < 90.0) {
        const Eigen::Vector2d n = surface_normal(map, hit.ix, hit.iy);
        // cos(incidence) = -ray . normal; a smooth surface seen too obliquely stays silent.
        if (n.norm() > 0.0 && -(ux * n.x() + uy * n.y()) < cos_spec) continue;
      }
      best = t;
    }
    // Draw every random number whatever happens, so one option never shifts another's stream.
    const double u_drop = rng.uniform(), u_cross = rng.uniform(), u_short = rng.uniform();
    const double noise = rng.gaussian();
    double d = best;
    if (std::isfinite(d)) d += noise * (o.range_sigma_m + o.range_sigma_frac * d);
    if (u_cross < o.crosstalk_prob) {
      const double upper = std::isfinite(best) ? std::min(best, s.max_range) : s.max_range;
      d = s.min_range + u_short * (upper - s.min_range);
    }
    if (u_drop < o.dropout_prob) d = s.max_range;
    if (!std::isfinite(d) || d >= s.max_range) d = s.max_range;
    ranges.push_back(std::max(d, s.min_range));
  }
  return ranges;
}

}  // namespace gridloc
