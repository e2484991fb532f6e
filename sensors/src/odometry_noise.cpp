// Seeded systematic odometry error: one length scale and one heading drift per run.
#include "gridloc/sensors/odometry_noise.hpp"

#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const OdometryNoise& noise) {
  if (!(noise.frac >= 0.0) || !std::isfinite(noise.frac)) {
    throw Error("odometry noise: the length share must be finite and >= 0, got " +
                std::to_string(noise.frac));
  }
  if (!(noise.rad_per_m >= 0.0) || !std::isfinite(noise.rad_per_m)) {
    throw Error("odometry noise: the heading drift must be finite and >= 0, got " +
                std::to_string(noise.rad_per_m));
  }
}

std::vector<Pose2> drifting_odometry(const std::vector<Pose2>& path, const OdometryNoise& noise,
                                     Rng& rng) {
  validate(noise);
  if (path.empty()) return {};
  const double scale = 1.0 + noise.frac * rng.gaussian();
  const double drift_per_m = noise.rad_per_m * rng.gaussian();
  std::vector<Pose2> odometry{path.front()};
  odometry.reserve(path.size());
  for (std::size_t k = 1; k < path.size(); ++k) {
    Pose2 step = relative_pose(path[k - 1], path[k]);
    const double length = std::hypot(step.x, step.y);
    step.x *= scale;
    step.y *= scale;
    step.theta += drift_per_m * length;
    odometry.push_back(compose(odometry.back(), step));
  }
  return odometry;
}

}  // namespace gridloc
