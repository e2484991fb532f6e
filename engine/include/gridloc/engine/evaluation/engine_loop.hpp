#pragma once
/// The simulated wheelchair with the engine in the loop (issue 15, beyond seed 002): on an
/// occupancy map, the hypotheses the correlation engine's global search leaves, and the
/// COL/UAL planner on the grid twin (GridPlanningSpace) driven by a robot that follows each
/// route with odometry error, fires its sonar ring (or laser) along the way with realistic
/// noise and lets the engine's own windowed scores, summed over the stops, rule hypotheses
/// out; beside it the same planner with noise-free sensing and motion.
#include <cstdint>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/disambiguation/disambiguation_planner.hpp"
#include "gridloc/engine/disambiguation/grid_space.hpp"
#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/score_elimination.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/engine/localizer/hypothesis_set.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/odometry_noise.hpp"

namespace gridloc {

struct EngineLoopOptions {
  /// The laser (enabled) or the sonar ring (disabled) observes; its max range (or the ring's
  /// farthest sonar) is also the planner's sensor range.
  LaserProtocol laser;
  CorrelationOptions correlation;  ///< the engine (its reach covers the fused drive)
  HypothesisSetOptions seeding;    ///< the hypotheses a global search leaves
  ScoreEliminationOptions elimination;
  OdometryNoise odometry;  ///< on every route
  /// The robot fires its ring (or scans) every this many metres along a route, and the
  /// firings within `drive` of the stop are fused into its observation there.
  double firing_every_m = 0.25;
  DriveWindowOptions drive;
  /// COL or UAL, the strategy, the points; the chair moves at least a firing's spacing to a
  /// stop (a noisy reading that ruled nothing out is not taken again on the spot) and gives up
  /// after 12 stops (a twin no drive tells apart would keep it going).
  MinimumDistanceOptions planner{.max_stops = 12, .min_travel_m = 0.25};
  ScanEquivalence equivalence;  ///< the grid twin's predicted views
  /// Routes and stops keep the robot's centre this far from walls (the wheelchair's half
  /// width, 0.35 m, and 5 cm): GridSpaceOptions::clearance_m.
  double route_clearance_m = 0.4;
  /// The true hypothesis is the one within these of the true start (m, rad).
  double truth_xy = 0.3;
  double truth_theta = 0.2618;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const EngineLoopOptions& options);

/// The real chair's planner the simulated one uses: the sensor, engine, seeding, drive window
/// and planner of `options`.
DisambiguationPlannerOptions as_planner_options(const EngineLoopOptions& options);

/// One simulated run from a true start.
struct EngineLoopRun {
  std::vector<Pose2> hypotheses;   ///< the global search's look-alikes
  int true_hypothesis = -1;        ///< the one within truth_xy / truth_theta of the truth
  MinimumDistancePlan plan;        ///< the engine in the loop
  MinimumDistancePlan noise_free;  ///< perfect sensing and motion on the grid twin
};

/// The simulated chair around a DisambiguationPlanner (which answers hypotheses() and
/// next_stop() as for a real chair).
class EngineLoop {
 public:
  /// Builds the planner (the estimator and the grid twin) once; throws gridloc::Error for bad
  /// options.
  EngineLoop(const OccupancyMap& map, const SonarRing& ring, const EngineLoopOptions& options);

  /// The observation at `truth`: one firing of the ring (or one scan) with realistic noise.
  Observation observe(const Pose2& truth, std::uint64_t seed) const;
  /// DisambiguationPlanner::hypotheses.
  std::vector<Pose2> hypotheses(const Observation& observation) const {
    return planner_.hypotheses(observation);
  }
  /// The index of the hypothesis within truth_xy and truth_theta of `truth`, or -1.
  int true_hypothesis(const std::vector<Pose2>& hypotheses, const Pose2& truth) const;
  /// Runs the planner from `truth` (hypotheses as hypotheses() gave them) both ways.
  EngineLoopRun run(const Pose2& truth, std::vector<Pose2> hypotheses, std::uint64_t seed) const;
  /// DisambiguationPlanner::next_stop.
  MinimumDistancePlan next_stop(const std::vector<Pose2>& hypotheses, std::uint64_t seed) const {
    return planner_.next_stop(hypotheses, seed);
  }

  const OccupancyMap& map() const { return map_; }
  const SonarRing& ring() const { return ring_; }
  const GridPlanningSpace& space() const { return planner_.space(); }
  const CorrelationEstimator& estimator() const { return planner_.estimator(); }
  const DisambiguationPlanner& planner() const { return planner_; }
  const EngineLoopOptions& options() const { return options_; }

 private:
  OccupancyMap map_;
  SonarRing ring_;
  EngineLoopOptions options_;
  DisambiguationPlanner planner_;
};

}  // namespace gridloc
