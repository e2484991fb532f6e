// Planned disambiguation for a real chair (see disambiguation_planner.hpp).
#include "gridloc/engine/disambiguation/disambiguation_planner.hpp"

#include <algorithm>

namespace gridloc {
namespace {

bool on_free_cell(const OccupancyMap& map, const Pose2& pose) {
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(local.x, local.y);
  return map.geometry.contains(cell.ix, cell.iy) && map.at(cell.ix, cell.iy) == CellState::Free;
}

/// The farthest a sonar of the ring hears (m): the planner's sensor range.
double sonar_range(const SonarRing& ring) {
  double range = 0.0;
  for (const SonarSpec& sonar : ring.sonars) range = std::max(range, sonar.max_range);
  return range;
}

CorrelationOptions engine_options(const DisambiguationPlannerOptions& options, double ring_reach) {
  CorrelationOptions correlation = options.correlation;
  // The fused drive reaches as far as its oldest firing's sensors (the Localizer's rule).
  correlation.reach_m =
      (options.laser ? options.laser_range_m : ring_reach) + options.drive.max_distance_m;
  return correlation;
}

CorrelationEstimator make_estimator(const OccupancyMap& map, const SonarRing& ring,
                                    const DisambiguationPlannerOptions& options) {
  validate(options);
  const CorrelationOptions correlation = engine_options(options, ring.reach());
  return options.laser ? CorrelationEstimator(map, correlation)
                       : CorrelationEstimator(map, ring, correlation);
}

GridSpaceOptions space_options(const SonarRing& ring, const DisambiguationPlannerOptions& options) {
  const double range = options.laser ? options.laser_range_m : sonar_range(ring);
  return {range, options.equivalence, options.route_clearance_m};
}

/// Nothing sensed yet: every hypothesis stands.
StopReading nothing_sensed(const Eigen::Vector2d&, const std::vector<Eigen::Vector2d>&,
                           const std::vector<int>& active) {
  return {active, {}};
}

}  // namespace

void validate(const DisambiguationPlannerOptions& options) {
  validate(options.planner);
  validate(options.seeding);
  validate(options.drive);
}

DisambiguationPlanner::DisambiguationPlanner(const OccupancyMap& map, const SonarRing& ring,
                                             const DisambiguationPlannerOptions& options)
    : options_(options),
      estimator_(make_estimator(map, ring, options)),
      space_(map, space_options(ring, options)) {}

std::vector<Pose2> DisambiguationPlanner::hypotheses(const Observation& observation) const {
  const HypothesisSetOptions& seeding = options_.seeding;
  const Estimate global = estimator_.estimate(observation, estimator_.global_window(observation),
                                              seeding.max_hypotheses + 1);
  std::vector<Pose2> poses;
  for (const TrackedHypothesis& seed : seed_hypotheses(global, seeding).hypotheses) {
    if (passable(seed.pose)) poses.push_back(seed.pose);
  }
  return poses;
}

MinimumDistancePlan DisambiguationPlanner::next_stop(const std::vector<Pose2>& hypotheses,
                                                     std::uint64_t seed) const {
  MinimumDistanceOptions planner = options_.planner;
  planner.seed = seed;
  planner.max_stops = 1;
  return localize_with_minimum_travel(space_, hypotheses, nothing_sensed, planner);
}

bool DisambiguationPlanner::passable(const Pose2& pose) const {
  return on_free_cell(space_.passable(), pose);
}

}  // namespace gridloc
