#pragma once
/// Seed 001's evaluation protocol (§4, §6): random poses in free space away from walls, a
/// prior perturbed uniformly within the search window, simulated sonar readings; success when
/// the position error <= 10 cm and the heading error <= 7 deg. Every configuration sees the
/// same poses, priors and readings. The trials are drawn by trials.hpp, the calibration
/// measures are metrics.hpp's.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/calibration.hpp"
#include "gridloc/sensors/echo_filter.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {

struct EvalConfiguration {
  LocalModel local = LocalModel::Oriented;
  GlobalModel global = GlobalModel::Thinned;
  /// Icp and CorrelationIcp need the laser protocol; Icp ignores local and global.
  EstimatorKind estimator = EstimatorKind::Correlation;
};

/// The laser protocol (`gridloc eval --laser`): each trial simulates a 360 degree laser scan
/// (simulate_scan) from the true pose instead of the sonar ring, so ICP can run.
struct LaserProtocol {
  bool enabled = false;
  int beams = 360;
  double max_range = 8.0;  ///< m; also the correlation estimator's reach
  double sigma_m = 0.01;   ///< Gaussian range noise
};

/// The failure-provoking protocol of `gridloc eval --noisy`: each trial draws what can go
/// wrong, so that the confidence can be judged on failures (issue 4's calibration).
struct NoisyProtocol {
  bool enabled = false;
  /// Sensor noise: 3 cm + 2 % Gaussian, 5 % dropouts, specular loss beyond 60 deg of
  /// incidence, 5 % crosstalk (replaces EvalOptions::noise).
  SonarSimOptions noise = SonarSimOptions::harsh(1);
  double wrong_prior_prob = 0.15;  ///< the prior lies 1.5-3 window half-sizes off the truth
  double furniture_prob = 0.25;    ///< the world gains 2-4 boxes the map does not have
};

struct EvalOptions {
  int trials = 100;  ///< per map
  std::uint64_t seed = 1;
  double clearance_m = 0.25;  ///< free space required around the footprint
  SearchWindow window;        ///< its half sizes perturb the prior; its centre is ignored
  double success_xy = 0.10;
  double success_theta = 0.122173047640;                  ///< 7 deg
  SonarSimOptions noise = SonarSimOptions::realistic(1);  ///< its seed is replaced per trial
  CorrelationOptions search;  ///< its local/global fields are replaced per configuration
  NoisyProtocol noisy;        ///< when enabled, replaces `noise` and adds failures
  /// When enabled, trials observe with a laser (noisy still adds wrong priors and furniture;
  /// the sonar noise and the echo filter do not apply).
  LaserProtocol laser;
  /// When set (`gridloc eval --echo-filter`), each trial fires the ring `echo_firings` times
  /// from the same pose (the first firing is the reading of the unfiltered protocol, the others
  /// draw their noise, dropouts and crosstalk from seeds of their own), filters the firings
  /// with filter_echoes and localizes with the filtered readings and their rejection mask.
  /// Unset (default): one firing, exactly the protocol without the filter.
  std::optional<EchoFilterOptions> echo_filter = std::nullopt;
  int echo_firings = 3;  ///< consecutive firings per trial when echo_filter is set (>= 2)
  std::vector<EvalConfiguration> configurations = {{LocalModel::Turned, GlobalModel::Raw},
                                                   {LocalModel::Turned, GlobalModel::Thinned},
                                                   {LocalModel::Oriented, GlobalModel::Raw},
                                                   {LocalModel::Oriented, GlobalModel::Thinned}};
};

struct EvalMap {
  std::string name;
  OccupancyMap map;
};

struct ConfigurationResult {
  EvalConfiguration configuration;
  int trials = 0;
  int successes = 0;
  double success_rate = 0.0;
  double mean_position_error_m = 0.0;   ///< over all trials
  double mean_heading_error_deg = 0.0;  ///< over all trials
  double median_ms = 0.0;               ///< estimate() wall time
  /// How well Estimate::confidence separates successes from failures: the probability that a
  /// random success has a higher confidence than a random failure (ties count half); NaN
  /// without both successes and failures.
  double auroc = 0.0;
  /// The share of failures whose confidence lies below the threshold that keeps 95 % of
  /// the successes (their 5th percentile); NaN without both.
  double failures_flagged_at_95_recall = 0.0;
  /// How well the `localized` answers' covariances cover their errors (issue 19).
  CalibrationSummary calibration;
};

/// One trial of one configuration, for calibration studies (`gridloc eval --trials-out`).
struct TrialRecord {
  std::string map;
  int trial = 0;
  std::size_t configuration = 0;  ///< index into EvalOptions::configurations
  bool success = false;
  bool wrong_prior = false;  ///< the noisy protocol put the prior off (truth outside the window)
  bool furniture = false;    ///< the noisy protocol changed the world
  double position_error_m = 0.0;
  double heading_error_deg = 0.0;
  Estimate estimate;
  int rejected_sonars = 0;  ///< sonars the echo filter rejected (0 without it)
  Pose2 truth;              ///< where the robot was
};

struct EvalReport {
  int trials = 0;  ///< over all maps
  std::vector<ConfigurationResult> configurations;
  std::vector<TrialRecord> records;  ///< every trial of every configuration, in run order
};

/// Runs the protocol on each map. `progress(done, total)` is called after every trial.
EvalReport run_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                          const EvalOptions& options,
                          const std::function<void(int, int)>& progress = {});

std::string to_string(LocalModel m);
std::string to_string(GlobalModel m);

}  // namespace gridloc
