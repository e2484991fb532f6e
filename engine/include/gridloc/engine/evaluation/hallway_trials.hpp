#pragma once
/// Seed 004 §4's simulation of robust ICP, repeated over seeds (`gridloc hallway`): a 720-point
/// scan of seed004_hallway() at the origin as reference, one after the motion (0.5 m, -0.2 m,
/// 20 deg) as current, both with seeded range noise, the current one with outliers; ICP from
/// the zero pose. Seed s draws the noise from seeds 1000 + 2s and 1001 + 2s, the outliers from s.
#include <cstdint>
#include <string>

#include "gridloc/engine/icp/robust_icp.hpp"

namespace gridloc {

enum class OutlierKind {
  None,
  Scattered,  ///< scatter_outliers within 3 m: spurious returns
  Appearing,  ///< appear_obstacles: four runs pulled 20-60 % closer
};

/// "none", "scattered", "appearing"; parse_outlier_kind throws gridloc::Error otherwise.
std::string to_string(OutlierKind kind);
OutlierKind parse_outlier_kind(const std::string& name);

struct HallwayTrialsOptions {
  int seeds = 100;  ///< runs with seeds 1..seeds
  double noise_m = 0.0;
  OutlierKind outliers = OutlierKind::None;
  double share = 0.3;
  IcpOptions icp;
  /// A run succeeds within these of the motion (m, deg).
  double success_xy = 0.001;
  double success_deg = 0.01;
};

struct HallwayReport {
  int seeds = 0;
  int successes = 0;
  int converged = 0;
  /// Over the successful runs (0 without any): absolute errors as seed 004 reports them.
  double mean_error_x_m = 0.0;
  double mean_error_y_m = 0.0;
  double mean_error_deg = 0.0;
  double mean_iterations = 0.0;
};

/// The pose seed 004 §4 moves the robot by.
inline const Pose2 kSeed004Motion{0.5, -0.2, 0.349065850399};  // 20 deg

/// Runs the trials; throws gridloc::Error for seeds < 1 or a bad option.
HallwayReport run_hallway_trials(const HallwayTrialsOptions& options);

}  // namespace gridloc
