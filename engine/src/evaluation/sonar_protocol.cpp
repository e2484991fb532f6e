// Seed 001's evaluation protocol (sonar_protocol.hpp): per map, one estimator per
// configuration; per trial, one draw of truth, world, readings and prior that every
// configuration then localizes with.
#include "gridloc/engine/evaluation/sonar_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "gridloc/engine/evaluation/metrics.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/engine/icp/estimator.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "seeds.hpp"

namespace gridloc {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// An estimator shared with another owner (the correlation search of CorrelationIcp).
class SharedEstimator final : public Estimator {
 public:
  explicit SharedEstimator(std::shared_ptr<const Estimator> estimator)
      : estimator_(std::move(estimator)) {}
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override {
    return estimator_->estimate(observation, window);
  }
  std::string name() const override { return estimator_->name(); }

 private:
  std::shared_ptr<const Estimator> estimator_;
};

/// Throws gridloc::Error for options the protocol cannot run.
void check(const EvalOptions& options, std::size_t maps) {
  if (options.trials < 1) throw Error("evaluation: trials must be >= 1");
  if (maps == 0) throw Error("evaluation: no maps");
  if (options.echo_filter) {
    validate(*options.echo_filter);
    if (options.echo_firings < 2) {
      throw Error("evaluation: echo_firings must be >= 2, got " +
                  std::to_string(options.echo_firings));
    }
  }
  const LaserProtocol& laser = options.laser;
  if (laser.enabled && options.echo_filter) {
    throw Error("evaluation: the echo filter is for sonar readings, not the laser protocol");
  }
  for (const auto& configuration : options.configurations) {
    if (is_sector_estimator(configuration.estimator)) {
      throw Error("evaluation: the " + to_string(configuration.estimator) +
                  " estimator needs polygon maps and global 360 degree scans: the sector "
                  "protocol (run_sector_evaluation; gridloc eval with polygon --maps)");
    }
    if (configuration.estimator != EstimatorKind::Correlation && !laser.enabled) {
      throw Error("evaluation: the " + to_string(configuration.estimator) +
                  " estimator needs laser scans (the laser protocol, gridloc eval --laser): "
                  "ICP finds no tangents in a sonar ring's echoes");
    }
  }
}

/// The correlation search's options of one configuration.
CorrelationOptions correlation_options(const EvalOptions& options,
                                       const EvalConfiguration& configuration) {
  CorrelationOptions correlation = options.search;
  correlation.local = configuration.local;
  correlation.global = configuration.global;
  correlation.reach_m = options.laser.enabled ? options.laser.max_range : 0.0;
  return correlation;
}

/// One estimator per configuration on `map`, in configuration order; the ICP configurations
/// share one IcpEstimator.
std::vector<std::unique_ptr<Estimator>> make_estimators(const OccupancyMap& map,
                                                        const SonarRing& ring,
                                                        const EvalOptions& options) {
  std::vector<std::unique_ptr<Estimator>> estimators;
  std::shared_ptr<const IcpEstimator> icp;  // one per map, shared by the ICP configurations
  for (const auto& configuration : options.configurations) {
    const CorrelationOptions search = correlation_options(options, configuration);
    if (configuration.estimator != EstimatorKind::Correlation && !icp) {
      icp = std::make_shared<const IcpEstimator>(map);
    }
    if (configuration.estimator == EstimatorKind::Icp) {
      estimators.push_back(std::make_unique<IcpEstimator>(*icp));
      continue;
    }
    auto correlation = options.laser.enabled
                           ? std::make_shared<CorrelationEstimator>(map, search)
                           : std::make_shared<CorrelationEstimator>(map, ring, search);
    if (configuration.estimator == EstimatorKind::CorrelationIcp) {
      estimators.push_back(std::make_unique<CorrelationIcpEstimator>(correlation, icp));
    } else {
      estimators.push_back(std::make_unique<SharedEstimator>(correlation));
    }
  }
  return estimators;
}

/// What one trial draws; every configuration localizes with the same.
struct Trial {
  Pose2 truth;
  bool furniture = false;    ///< the world gained boxes the map does not have
  bool wrong_prior = false;  ///< the truth lies outside the window
  Observation observation;
  int rejected_sonars = 0;    ///< by the echo filter
  bool all_rejected = false;  ///< the echo filter left nothing to localize with
  SearchWindow window;
};

/// The distance of the footprint's farthest corner from the robot's centre.
double footprint_radius(const Footprint& footprint) {
  double radius = 0.0;
  for (const auto& p : footprint.polygon) radius = std::max(radius, p.norm());
  return radius;
}

/// The observation from `truth` in `world`: a laser scan, or the sonar ring's readings.
Observation observe(const OccupancyMap& world, const SonarRing& ring, const Pose2& truth,
                    const SonarSimOptions& noise, const LaserProtocol& laser) {
  Observation observation;
  if (laser.enabled) {
    observation.scan =
        simulate_scan(world, truth, laser.beams, laser.max_range, laser.sigma_m, noise.seed);
  } else {
    observation.ranges = simulate_sonar(world, ring, truth, noise);
  }
  return observation;
}

/// Replaces the readings of `observation` by the echo filter's over `firings` consecutive
/// firings, the first of which is `observation`'s; returns the number of rejected sonars.
int filter_firings(const OccupancyMap& world, const SonarRing& ring, const Pose2& truth,
                   const SonarSimOptions& noise, const EvalOptions& options,
                   Observation& observation) {
  // Consecutive firings from the same pose: the first is the unfiltered protocol's
  // reading, the others draw from seeds derived from it (not from the trial's Rng, so that
  // poses and priors stay those of the unfiltered protocol).
  std::vector<std::vector<double>> firings{observation.ranges};
  for (int k = 1; k < options.echo_firings; ++k) {
    SonarSimOptions again = noise;
    again.seed = mix(noise.seed, static_cast<std::uint64_t>(k));
    firings.push_back(simulate_sonar(world, ring, truth, again));
  }
  FilteredReadings filtered = filter_echoes(ring, firings, *options.echo_filter);
  observation.ranges = std::move(filtered.ranges);
  observation.rejected = std::move(filtered.rejected);
  return filtered.rejected_count;
}

/// Sets the trial's observation in `world` (and its echo filtering).
void observe_trial(const OccupancyMap& world, const SonarRing& ring, const SonarSimOptions& noise,
                   const EvalOptions& options, Trial& trial) {
  trial.observation = observe(world, ring, trial.truth, noise, options.laser);
  if (options.echo_filter) {
    trial.rejected_sonars =
        filter_firings(world, ring, trial.truth, noise, options, trial.observation);
  }
  trial.all_rejected = trial.rejected_sonars == static_cast<int>(ring.sonars.size());
}

/// Trial `t` on the map at index `map_index`. Its draws, in this order, are the protocol:
/// the truth, the noise seed, (noisy only) furniture and wrong prior, the furniture, the prior.
Trial draw_trial(const OccupancyMap& map, std::size_t map_index, int t, const SonarRing& ring,
                 const EvalOptions& options) {
  Rng rng(trial_seed(options.seed, map_index, t));
  Trial trial;
  trial.truth = sample_free_pose(map, ring, options.clearance_m, rng);
  const NoisyProtocol& noisy = options.noisy;
  SonarSimOptions noise = noisy.enabled ? noisy.noise : options.noise;
  noise.seed = rng.next();
  // Only the noisy protocol draws these, so the plain protocol's draws stay as they were
  // (a noisy run's priors differ from a plain run's).
  trial.furniture = noisy.enabled && rng.uniform(0.0, 1.0) < noisy.furniture_prob;
  const bool wrong_prior = noisy.enabled && rng.uniform(0.0, 1.0) < noisy.wrong_prior_prob;
  if (trial.furniture) {
    const OccupancyMap changed =
        add_furniture(map, trial.truth, footprint_radius(ring.footprint) + 0.3, rng);
    observe_trial(changed, ring, noise, options, trial);
  } else {
    observe_trial(map, ring, noise, options, trial);
  }
  const PerturbedPrior prior =
      perturb_prior(options.window, trial.truth, wrong_prior, map.geometry, rng);
  trial.window = prior.window;
  trial.wrong_prior = prior.wrong_prior;
  return trial;
}

/// The errors, times and successes of one configuration, in run order.
struct ConfigurationTally {
  std::vector<double> position_errors;  ///< m
  std::vector<double> heading_errors;   ///< deg
  std::vector<double> ms;
  int successes = 0;
};

/// Localizes trial `t` of map `map_name` with every configuration's estimator; tallies and
/// records the outcomes.
void score_trial(const Trial& trial, const std::string& map_name, int t,
                 const std::vector<std::unique_ptr<Estimator>>& estimators,
                 const EvalOptions& options, std::vector<ConfigurationTally>& tallies,
                 EvalReport& report) {
  const Pose2& truth = trial.truth;
  for (std::size_t c = 0; c < tallies.size(); ++c) {
    Estimate estimate;
    if (trial.all_rejected) {  // nothing to localize with: a failure at the prior, no confidence
      estimate.pose = estimate.lattice_pose = trial.window.center;
    } else {
      estimate = estimators[c]->estimate(trial.observation, trial.window);
    }
    const double position_error = std::hypot(estimate.pose.x - truth.x, estimate.pose.y - truth.y);
    const double heading_error = std::abs(normalize_angle(estimate.pose.theta - truth.theta));
    ConfigurationTally& tally = tallies[c];
    tally.position_errors.push_back(position_error);
    tally.heading_errors.push_back(rad2deg(heading_error));
    tally.ms.push_back(estimate.stats.elapsed_ms);
    const bool success =
        position_error <= options.success_xy && heading_error <= options.success_theta;
    if (success) ++tally.successes;
    report.records.push_back({map_name, t, c, success, trial.wrong_prior, trial.furniture,
                              position_error, rad2deg(heading_error), estimate,
                              trial.rejected_sonars, truth});
  }
}

/// Configuration `c`'s result over all `total` trials.
ConfigurationResult summarize(const EvalOptions& options, std::size_t c, int total,
                              const ConfigurationTally& tally,
                              const std::vector<TrialRecord>& records) {
  std::vector<double> good, bad;  // confidences of successes and failures
  std::vector<CalibrationSample> samples;
  for (const TrialRecord& record : records) {
    if (record.configuration == c) {
      (record.success ? good : bad).push_back(record.estimate.confidence);
      const Estimate& e = record.estimate;
      samples.push_back({e.pose, e.covariance, record.truth, e.verdict == Verdict::Localized});
    }
  }
  ConfigurationResult result;
  result.configuration = options.configurations[c];
  result.trials = total;
  result.successes = tally.successes;
  result.success_rate = static_cast<double>(tally.successes) / total;
  for (double v : tally.position_errors) result.mean_position_error_m += v / total;
  for (double v : tally.heading_errors) result.mean_heading_error_deg += v / total;
  result.median_ms = median(tally.ms);
  result.auroc = auroc(good, bad);
  result.failures_flagged_at_95_recall = flagged_at_recall(good, bad, 0.95);
  result.calibration = summarize_calibration(samples);
  return result;
}

}  // namespace

std::string to_string(LocalModel m) {
  return m == LocalModel::Oriented ? "oriented" : "turned";
}
std::string to_string(GlobalModel m) {
  return m == GlobalModel::Thinned ? "thinned" : m == GlobalModel::Raw ? "raw" : "field";
}

EvalReport run_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                          const EvalOptions& options,
                          const std::function<void(int, int)>& progress) {
  check(options, maps.size());
  std::vector<ConfigurationTally> tallies(options.configurations.size());
  const int total = options.trials * static_cast<int>(maps.size());
  int done = 0;
  EvalReport report;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const auto estimators = make_estimators(maps[m].map, ring, options);
    for (int t = 0; t < options.trials; ++t) {
      const Trial trial = draw_trial(maps[m].map, m, t, ring, options);
      score_trial(trial, maps[m].name, t, estimators, options, tallies, report);
      if (progress) progress(++done, total);
    }
  }
  report.trials = total;
  for (std::size_t c = 0; c < tallies.size(); ++c) {
    report.configurations.push_back(summarize(options, c, total, tallies[c], report.records));
  }
  return report;
}

}  // namespace gridloc
