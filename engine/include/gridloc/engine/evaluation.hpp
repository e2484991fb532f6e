#pragma once
/// Seed 001's evaluation protocol (§4, §6): random poses in free space away from walls, a
/// prior perturbed uniformly within the search window, simulated sonar readings; success when
/// the position error <= 10 cm and the heading error <= 7 deg. Every configuration sees the
/// same poses, priors and readings.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation_estimator.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {

struct EvalConfiguration {
  LocalModel local = LocalModel::Oriented;
  GlobalModel global = GlobalModel::Thinned;
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
};

struct EvalReport {
  int trials = 0;  ///< over all maps
  std::vector<ConfigurationResult> configurations;
};

/// Draws a pose uniformly in the map whose footprint, grown by `clearance`, covers only free
/// cells. Throws gridloc::Error when none is found in many attempts.
Pose2 sample_free_pose(const OccupancyMap& map, const SonarRing& ring, double clearance, Rng& rng);

/// Runs the protocol on each map. `progress(done, total)` is called after every trial.
EvalReport run_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                          const EvalOptions& options,
                          const std::function<void(int, int)>& progress = {});

std::string to_string(LocalModel m);
std::string to_string(GlobalModel m);

}  // namespace gridloc
