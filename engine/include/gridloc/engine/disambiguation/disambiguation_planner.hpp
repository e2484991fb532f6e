#pragma once
/// Planned disambiguation for a real chair on an occupancy map (issue 15): the look-alikes
/// the correlation engine's global search leaves for what the chair sensed at its start, and
/// the COL/UAL planner's first stop on the grid twin (GridPlanningSpace). The chair drives
/// there, senses and asks again. The simulated chair of evaluation/engine_loop.hpp holds one.
#include <cstdint>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/disambiguation/grid_space.hpp"
#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/localizer/hypothesis_set.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

struct DisambiguationPlannerOptions {
  /// The sensor: a laser of this range (laser true) or the sonar ring; its range (the ring's
  /// farthest sonar) is also the planner's sensor range.
  bool laser = false;
  double laser_range_m = 8.0;
  CorrelationOptions correlation;  ///< the engine (its reach covers the fused drive)
  HypothesisSetOptions seeding;    ///< the hypotheses a global search leaves
  /// The firings (or scans) within this of a stop are fused into the observation there (as
  /// the Localizer does); the engine's reach covers it.
  DriveWindowOptions drive;
  /// COL or UAL, the strategy, the points; the chair moves at least a firing's spacing to a
  /// stop (a noisy reading that ruled nothing out is not taken again on the spot) and gives up
  /// after 12 stops (a twin no drive tells apart would keep it going).
  MinimumDistanceOptions planner{.max_stops = 12, .min_travel_m = 0.25};
  ScanEquivalence equivalence;  ///< the grid twin's predicted views
  /// Routes and stops keep the robot's centre this far from walls (the wheelchair's half
  /// width, 0.35 m, and 5 cm): GridSpaceOptions::clearance_m.
  double route_clearance_m = 0.4;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const DisambiguationPlannerOptions& options);

class DisambiguationPlanner {
 public:
  /// Builds the estimator and the grid twin once; throws gridloc::Error for bad options.
  DisambiguationPlanner(const OccupancyMap& map, const SonarRing& ring,
                        const DisambiguationPlannerOptions& options);

  /// The look-alikes the global search leaves for `observation` (a HypothesisSet's seeds on
  /// cells the chair can reach, GridPlanningSpace::passable), best first.
  std::vector<Pose2> hypotheses(const Observation& observation) const;
  /// Where to drive first: the planner's first stop, nothing sensed yet (a real robot
  /// drives there, observes and asks again).
  MinimumDistancePlan next_stop(const std::vector<Pose2>& hypotheses, std::uint64_t seed) const;
  /// Whether `pose` stands on a cell the chair can reach (GridPlanningSpace::passable).
  bool passable(const Pose2& pose) const;

  const CorrelationEstimator& estimator() const { return estimator_; }
  const GridPlanningSpace& space() const { return space_; }
  const DisambiguationPlannerOptions& options() const { return options_; }

 private:
  DisambiguationPlannerOptions options_;
  CorrelationEstimator estimator_;
  GridPlanningSpace space_;
};

}  // namespace gridloc
