#pragma once
/// Seed 002's protocol (§V): random office environments of about 400 vertices on a grid of
/// 1-unit cells, three ambiguous start locations each, every run repeated with another seed
/// of the random points (20 x 3 x 2 = 120 trials), for each algorithm (COL, UAL), distance
/// strategy (standard weighted, hybrid), number of random points and sensor range; the
/// lower bound of travel_lower_bound() beside every mean.
#include <cstdint>
#include <functional>
#include <vector>

#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/engine/evaluation/office_environments.hpp"

namespace gridloc {

struct DisambiguationProtocolOptions {
  int environments = 20;  ///< random offices (seeds 1..environments)
  int starts = 3;         ///< ambiguous start locations per office
  int repeats = 2;        ///< runs per start, each with its own seed of the random points
  std::vector<int> points = {1, 5, 10, 40, 80, 250, 500};
  /// In cell units (seed 002's 500, 200, 90 pixels are 5, 2, 0.9 cells); kUnlimitedRange
  /// for its unlimited visibility.
  std::vector<double> ranges = {kUnlimitedRange, 5.0, 2.0, 0.9};
  std::vector<SamplingAlgorithm> algorithms = {SamplingAlgorithm::Col, SamplingAlgorithm::Ual};
  std::vector<DistanceStrategy> strategies = {DistanceStrategy::Weighted, DistanceStrategy::Hybrid};
  std::uint64_t seed = 1;  ///< of the start locations (offices use seeds 1..environments)
  /// Random points tried per office before it is given up for want of ambiguous starts.
  int start_attempts = 20000;
  OfficeOptions office;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const DisambiguationProtocolOptions& options);

/// `count` start locations (heading 0: the compass) drawn uniformly over the office's free
/// space, each ambiguous at every range of the run (at least two hypotheses at the largest
/// range) and seeing a map vertex within the smallest (so that its hypotheses are a finite
/// set, seed 002 §III). Throws gridloc::Error when `attempts` draws find fewer.
std::vector<Pose2> ambiguous_starts(const PolygonMap& office, int count,
                                    const std::vector<double>& ranges, std::uint64_t seed,
                                    int attempts);

struct DisambiguationConfiguration {
  SamplingAlgorithm algorithm = SamplingAlgorithm::Ual;
  DistanceStrategy strategy = DistanceStrategy::Hybrid;
  int points = 0;
  double range = kUnlimitedRange;
  int trials = 0;
  double mean_path_length = 0.0;
  double resolved_rate = 0.0;
  double mean_stops = 0.0;
  double mean_lower_bound = 0.0;  ///< over the same trials (finite bounds)
  /// The mean over trials of path length / lower bound (trials with a positive bound).
  double mean_bound_ratio = 0.0;
  /// The same for travel_lower_bound()'s pairwise bound (the truth is known here).
  double mean_pairwise_bound = 0.0;
  double mean_pairwise_ratio = 0.0;
  double mean_hypotheses = 0.0;
  double median_ms = 0.0;     ///< planning and sensing time per trial
  double mean_stop_ms = 0.0;  ///< the same per stop (trials with stops)
};

struct DisambiguationProtocolResult {
  int trials = 0;  ///< per configuration
  std::vector<DisambiguationConfiguration> configurations;
};

/// Runs the protocol; `progress(done, total)` after every trial of every configuration.
DisambiguationProtocolResult run_disambiguation_protocol(
    const DisambiguationProtocolOptions& options,
    const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
