// Seed 002 §V's protocol (see disambiguation_protocol.hpp).
#include "gridloc/engine/evaluation/disambiguation_protocol.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"
#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/engine/disambiguation/polygon_space.hpp"
#include "gridloc/engine/disambiguation/sampling.hpp"
#include "gridloc/engine/disambiguation/travel_bound.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

/// One office with its starts, and per range each start's hypotheses and bound.
struct Environment {
  int seed = 0;
  Area free_world;
  std::vector<Pose2> starts;
  std::vector<std::vector<std::vector<Pose2>>> hypotheses;  ///< [range][start]
  std::vector<std::vector<TravelBound>> bounds;             ///< [range][start]
};

struct TrialOutcome {
  double path_length = 0.0, bound = 0.0, pairwise = 0.0, ms = 0.0;
  int stops = 0, hypotheses = 0;
  bool resolved = false;
};

bool sees_a_vertex(const Area& area, const Eigen::Vector2d& at, double range) {
  return visible_vertex_count(range_view(area, at, 0.0, range)) > 0;
}

Environment prepare_environment(int seed, const DisambiguationProtocolOptions& options) {
  Environment environment;
  environment.seed = seed;
  const PolygonMap office = random_office(static_cast<std::uint64_t>(seed), options.office);
  environment.free_world = free_area(office);
  environment.starts = ambiguous_starts(office, options.starts, options.ranges,
                                        options.seed * 1000003u + static_cast<std::uint64_t>(seed),
                                        options.start_attempts);
  for (const double range : options.ranges) {
    std::vector<std::vector<Pose2>> per_start;
    std::vector<TravelBound> bounds;
    for (const Pose2& start : environment.starts) {
      per_start.push_back(start_hypotheses(environment.free_world, start, {range, false, 1e-6}));
      const PolygonPlanningSpace space(environment.free_world, {range, 1e-6, 16});
      bounds.push_back(travel_lower_bound(space, per_start.back(),
                                          find_pose(per_start.back(), start), 0.0,
                                          std::isfinite(range) ? range / 4.0 : kUnlimitedRange));
    }
    environment.hypotheses.push_back(std::move(per_start));
    environment.bounds.push_back(std::move(bounds));
  }
  return environment;
}

TrialOutcome run_trial(const Environment& environment, std::size_t range_index, std::size_t start,
                       const MinimumDistanceOptions& options, double range) {
  const std::vector<Pose2>& hypotheses = environment.hypotheses[range_index][start];
  const Pose2& truth = environment.starts[start];
  const auto begin = std::chrono::steady_clock::now();
  const PolygonPlanningSpace space(environment.free_world, {range, 1e-6, 16});
  const MinimumDistancePlan plan = localize_with_minimum_travel(
      space, hypotheses, perfect_sensing(environment.free_world, truth, hypotheses, range),
      options);
  const auto end = std::chrono::steady_clock::now();
  TrialOutcome outcome;
  outcome.path_length = plan.path_length;
  outcome.bound = environment.bounds[range_index][start].distance;
  outcome.pairwise = environment.bounds[range_index][start].pairwise;
  outcome.ms = std::chrono::duration<double, std::milli>(end - begin).count();
  outcome.stops = static_cast<int>(plan.stops.size());
  outcome.hypotheses = static_cast<int>(hypotheses.size());
  outcome.resolved = plan.resolved && find_pose(hypotheses, truth) == plan.remaining.front();
  return outcome;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

double mean(const std::vector<double>& values) {
  return values.empty() ? 0.0
                        : std::accumulate(values.begin(), values.end(), 0.0) /
                              static_cast<double>(values.size());
}

DisambiguationConfiguration summarize(DisambiguationConfiguration row,
                                      const std::vector<TrialOutcome>& outcomes) {
  std::vector<double> lengths, bounds, pairwise, ratios, pairwise_ratios, ms, stop_ms, stops,
      hypotheses;
  int resolved = 0;
  for (const TrialOutcome& outcome : outcomes) {
    lengths.push_back(outcome.path_length);
    stops.push_back(outcome.stops);
    hypotheses.push_back(outcome.hypotheses);
    ms.push_back(outcome.ms);
    if (outcome.stops > 0) stop_ms.push_back(outcome.ms / outcome.stops);
    if (std::isfinite(outcome.bound)) bounds.push_back(outcome.bound);
    if (std::isfinite(outcome.bound) && outcome.bound > 0.0)
      ratios.push_back(outcome.path_length / outcome.bound);
    if (std::isfinite(outcome.pairwise)) pairwise.push_back(outcome.pairwise);
    if (std::isfinite(outcome.pairwise) && outcome.pairwise > 0.0)
      pairwise_ratios.push_back(outcome.path_length / outcome.pairwise);
    resolved += outcome.resolved ? 1 : 0;
  }
  row.trials = static_cast<int>(outcomes.size());
  row.mean_path_length = mean(lengths);
  row.resolved_rate = outcomes.empty() ? 0.0 : static_cast<double>(resolved) / row.trials;
  row.mean_stops = mean(stops);
  row.mean_lower_bound = mean(bounds);
  row.mean_bound_ratio = mean(ratios);
  row.mean_pairwise_bound = mean(pairwise);
  row.mean_pairwise_ratio = mean(pairwise_ratios);
  row.mean_hypotheses = mean(hypotheses);
  row.median_ms = median(ms);
  row.mean_stop_ms = mean(stop_ms);
  return row;
}

std::uint64_t trial_seed(int environment, std::size_t start, int repeat) {
  return 1000003ull * static_cast<std::uint64_t>(environment) + 1009ull * start +
         static_cast<std::uint64_t>(repeat) + 1;
}

struct Progress {
  const std::function<void(int, int)>& callback;
  int done = 0;
  int total = 0;
};

/// Every trial of one configuration: each office, start and repeat.
std::vector<TrialOutcome> run_configuration(const std::vector<Environment>& environments,
                                            std::size_t range_index,
                                            const DisambiguationConfiguration& row, int repeats,
                                            Progress& progress) {
  MinimumDistanceOptions planner;
  planner.algorithm = row.algorithm;
  planner.strategy = row.strategy;
  planner.points = row.points;
  std::vector<TrialOutcome> outcomes;
  for (const Environment& environment : environments) {
    for (std::size_t s = 0; s < environment.starts.size(); ++s) {
      for (int repeat = 0; repeat < repeats; ++repeat) {
        planner.seed = trial_seed(environment.seed, s, repeat);
        outcomes.push_back(run_trial(environment, range_index, s, planner, row.range));
        ++progress.done;
        if (progress.callback) progress.callback(progress.done, progress.total);
      }
    }
  }
  return outcomes;
}

}  // namespace

void validate(const DisambiguationProtocolOptions& options) {
  if (options.environments < 1) throw Error("disambiguation protocol: environments must be >= 1");
  if (options.starts < 1) throw Error("disambiguation protocol: starts must be >= 1");
  if (options.repeats < 1) throw Error("disambiguation protocol: repeats must be >= 1");
  if (options.start_attempts < 1)
    throw Error("disambiguation protocol: start_attempts must be >= 1");
  if (options.points.empty() || options.ranges.empty() || options.algorithms.empty() ||
      options.strategies.empty()) {
    throw Error("disambiguation protocol: points, ranges, algorithms and strategies need a value");
  }
  for (const int points : options.points) {
    if (points < 1 || points > 1000000) {
      throw Error("disambiguation protocol: points must be in [1, 1000000]");
    }
  }
  const double runs = static_cast<double>(options.environments) * options.starts * options.repeats *
                      static_cast<double>(options.points.size()) *
                      static_cast<double>(options.ranges.size() * options.algorithms.size() *
                                          options.strategies.size());
  if (runs > 1e8) {
    throw Error("disambiguation protocol: " + std::to_string(static_cast<long long>(runs)) +
                " runs (environments x starts x repeats x configurations) is more than 1e8");
  }
  for (const double range : options.ranges) {
    if (!(range > 0.0)) throw Error("disambiguation protocol: a range must be > 0");
  }
}

std::vector<Pose2> ambiguous_starts(const PolygonMap& office, int count,
                                    const std::vector<double>& ranges, std::uint64_t seed,
                                    int attempts) {
  const double smallest = *std::min_element(ranges.begin(), ranges.end());
  const double largest = *std::max_element(ranges.begin(), ranges.end());
  const Area free_world = free_area(office);
  Rng rng(seed);
  std::vector<Pose2> starts;
  for (int attempt = 0; attempt < attempts && static_cast<int>(starts.size()) < count; ++attempt) {
    const Eigen::Vector2d at = sample_uniform({free_world}, 1, rng).front();
    if (!sees_a_vertex(free_world, at, smallest)) continue;
    const Pose2 start{at.x(), at.y(), 0.0};
    if (start_hypotheses(free_world, start, {largest, false, 1e-6}).size() >= 2) {
      starts.push_back(start);
    }
  }
  if (static_cast<int>(starts.size()) < count) {
    throw Error("disambiguation protocol: " + std::to_string(attempts) +
                " random points found only " + std::to_string(starts.size()) + " of " +
                std::to_string(count) + " ambiguous starts");
  }
  return starts;
}

DisambiguationProtocolResult run_disambiguation_protocol(
    const DisambiguationProtocolOptions& options, const std::function<void(int, int)>& progress) {
  validate(options);
  std::vector<Environment> environments;
  for (int seed = 1; seed <= options.environments; ++seed) {
    environments.push_back(prepare_environment(seed, options));
  }
  DisambiguationProtocolResult result;
  result.trials = options.environments * options.starts * options.repeats;
  Progress counter{
      progress, 0,
      result.trials * static_cast<int>(options.algorithms.size() * options.strategies.size() *
                                       options.points.size() * options.ranges.size())};
  for (std::size_t r = 0; r < options.ranges.size(); ++r) {
    for (const SamplingAlgorithm algorithm : options.algorithms) {
      for (const DistanceStrategy strategy : options.strategies) {
        for (const int points : options.points) {
          const DisambiguationConfiguration row{algorithm, strategy, points, options.ranges[r]};
          result.configurations.push_back(
              summarize(row, run_configuration(environments, r, row, options.repeats, counter)));
        }
      }
    }
  }
  return result;
}

}  // namespace gridloc
