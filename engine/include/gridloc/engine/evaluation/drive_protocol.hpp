#pragma once
/// The drive protocol (issue 13): the wheelchair drives a short straight path after the
/// switch to autonomous mode, firing its ring along the way; the fused drive is localized
/// (sensors/drive_fusion.hpp) against the single firing at the end of the path, on the same
/// trials. Odometry drifts (seeded) as a miscalibrated one does: one length scale and one
/// heading drift per metre per trial.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {

struct DriveEvalOptions {
  int trials = 100;  ///< per map
  std::uint64_t seed = 1;
  double clearance_m = 0.25;          ///< free space around the footprint at every pose of the path
  double drive_m = 2.0;               ///< length of the straight path, the last firing at its end
  int firings = 5;                    ///< along the path, evenly spaced (>= 2)
  double odometry_noise_frac = 0.02;  ///< sigma of the trial's length scale error (a share)
  double odometry_noise_rad_per_m = 0.0174532925199;  ///< sigma of its heading drift (rad/m)
  /// No prior (global search) when true; otherwise seed 001's window around a prior drawn
  /// within it (perturb_prior), the same for both.
  bool global = true;
  SearchWindow window;  ///< the window's half sizes when not global
  SonarSimOptions noise = SonarSimOptions::realistic(1);  ///< its seed is replaced per firing
  DriveWindowOptions fusion;                              ///< which firings the drive keeps
  CorrelationOptions search;                              ///< reach_m is raised to cover the drive
  double success_xy = 0.10;
  double success_theta = 0.122173047640;  ///< 7 deg
};

/// One way of localizing (the single last firing, or the fused drive) over a map's trials.
struct DriveEvalTally {
  int successes = 0;
  int localized = 0;
  int ambiguous = 0;
  int not_localized = 0;
  int confident_wrong = 0;  ///< `localized` answers that are not successes
  double median_ms = 0.0;   ///< estimate() wall time
};

struct DriveEvalRow {
  std::string map;
  int trials = 0;
  DriveEvalTally standstill;  ///< the last firing alone
  DriveEvalTally drive;       ///< the fused drive
};

struct DriveEvalReport {
  std::vector<DriveEvalRow> maps;
};

/// Runs the protocol on each map (same trials for both ways). `progress(done, total)` is
/// called after every trial. Throws gridloc::Error for bad options or a map without room
/// for the drive.
DriveEvalReport run_drive_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                                     const DriveEvalOptions& options,
                                     const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
