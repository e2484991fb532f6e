#pragma once
/// Odometry off as a miscalibrated one is (issue 13): for logs and simulations whose poses
/// are exact, a seeded length-scale error and heading drift per metre applied to every step.
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

struct OdometryNoise {
  double frac = 0.02;                  ///< sigma of the run's length scale error (a share)
  double rad_per_m = 0.0174532925199;  ///< sigma of its heading drift (rad per metre)
  /// Slips (issue 34): on average every this many metres (exponential gaps, seeded) the
  /// odometry jumps by slip_m in a random direction and slip_rad either way; 0: no slips.
  double slip_every_m = 0.0;
  double slip_m = 0.3;
  double slip_rad = 0.174532925199;  ///< 10 deg
};

/// Checks the noise; throws gridloc::Error naming the field (finite, >= 0).
void validate(const OdometryNoise& noise);

/// The odometry of `path` (true poses in time order): one length scale and one heading drift
/// per metre drawn from `rng` (gaussian, sigma by `noise`) and applied to every step, so the
/// error grows with the distance driven whatever the number of poses. The first pose is the
/// odometry's origin. An empty path gives an empty odometry.
std::vector<Pose2> drifting_odometry(const std::vector<Pose2>& path, const OdometryNoise& noise,
                                     Rng& rng);

}  // namespace gridloc
