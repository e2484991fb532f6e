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
  const auto ok = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!ok(noise.slip_every_m) || !ok(noise.slip_m) || !ok(noise.slip_rad)) {
    throw Error("odometry noise: the slips' spacing, length and turn must be finite and >= 0");
  }
}

namespace {

/// The path to the next slip: exponential with mean `every_m`.
double next_slip_gap(double every_m, Rng& rng) {
  return -every_m * std::log(1.0 - rng.uniform());
}

/// A slip: slip_m in a random direction, slip_rad either way.
Pose2 slip(const OdometryNoise& noise, Rng& rng) {
  const double direction = rng.uniform(-3.14159265358979323846, 3.14159265358979323846);
  const double turn = rng.uniform() < 0.5 ? -noise.slip_rad : noise.slip_rad;
  return {noise.slip_m * std::cos(direction), noise.slip_m * std::sin(direction), turn};
}

}  // namespace

std::vector<Pose2> drifting_odometry(const std::vector<Pose2>& path, const OdometryNoise& noise,
                                     Rng& rng) {
  validate(noise);
  if (path.empty()) return {};
  const double scale = 1.0 + noise.frac * rng.gaussian();
  const double drift_per_m = noise.rad_per_m * rng.gaussian();
  const bool slips = noise.slip_every_m > 0.0;
  double to_slip = slips ? next_slip_gap(noise.slip_every_m, rng) : 0.0;
  std::vector<Pose2> odometry{path.front()};
  odometry.reserve(path.size());
  for (std::size_t k = 1; k < path.size(); ++k) {
    Pose2 step = relative_pose(path[k - 1], path[k]);
    const double length = std::hypot(step.x, step.y);
    step.x *= scale;
    step.y *= scale;
    step.theta += drift_per_m * length;
    odometry.push_back(compose(odometry.back(), step));
    to_slip -= length;
    while (slips && to_slip <= 0.0) {
      odometry.back() = compose(odometry.back(), slip(noise, rng));
      to_slip += next_slip_gap(noise.slip_every_m, rng);
    }
  }
  return odometry;
}

}  // namespace gridloc
