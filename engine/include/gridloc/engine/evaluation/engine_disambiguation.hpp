#pragma once
/// Seed 002 with the engine in the loop (issue 15, beyond the paper): on an occupancy map, the
/// robot starts where the correlation engine's global search leaves look-alikes; the COL/UAL
/// planner runs on the grid twin (GridPlanningSpace); at each stop the robot has driven its
/// route with odometry error, its sonar ring or laser reads with realistic noise, and the
/// engine's own windowed scores around each hypothesis's prediction rule hypotheses out
/// (eliminate_by_scores). Beside it, the same planner with noise-free sensing and motion.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/disambiguation/grid_views.hpp"
#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/score_elimination.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/engine/localizer/hypothesis_set.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/odometry_noise.hpp"

namespace gridloc {

struct EngineDisambiguationOptions {
  /// Ambiguous starts per map: poses are drawn until this many leave at least two
  /// hypotheses (at most `attempts_per_trial` draws each).
  int trials = 100;
  int attempts_per_trial = 20;
  std::uint64_t seed = 1;
  /// The laser (enabled) or the sonar ring (disabled) observes; its max range is also the
  /// planner's sensor range.
  LaserProtocol laser;
  CorrelationOptions correlation;  ///< the engine (its reach follows the laser's range)
  HypothesisSetOptions seeding;    ///< the hypotheses a global search leaves
  ScoreEliminationOptions elimination;
  OdometryNoise odometry;  ///< on every route
  /// The robot fires its ring (or scans) every this many metres along a route, and the
  /// firings within `drive` of the stop are fused into its observation there.
  double firing_every_m = 0.25;
  DriveWindowOptions drive;
  MinimumDistanceOptions planner;  ///< COL or UAL, the strategy, the points
  ScanEquivalence equivalence;     ///< the grid twin's predicted views
  double clearance_m = 0.3;        ///< true poses keep the footprint this far from walls
  /// Routes and stops keep the robot's centre this far from walls (the wheelchair's half
  /// width, 0.35 m, and 5 cm): GridSpaceOptions::clearance_m.
  double route_clearance_m = 0.4;
  /// The true hypothesis is the one within these of the true start (m, rad).
  double truth_xy = 0.3;
  double truth_theta = 0.2618;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const EngineDisambiguationOptions& options);

/// One map's results; the rates and means are NaN when no drawn pose was ambiguous.
struct EngineDisambiguationResult {
  std::string map;
  int trials = 0;                   ///< ambiguous starts run
  int drawn = 0;                    ///< poses drawn to find them (the rest were unique)
  int truth_seeded = 0;             ///< trials whose hypotheses held the truth
  double true_survived_rate = 0.0;  ///< the truth stood to the end (of trials)
  int wrong_answers = 0;            ///< resolved to a hypothesis that is not the truth
  double resolved_rate = 0.0;       ///< one hypothesis left
  double mean_hypotheses = 0.0;
  double mean_path_length = 0.0;             ///< engine in the loop
  double mean_noise_free_path_length = 0.0;  ///< the same starts, perfect sensing and motion
  double noise_free_resolved_rate = 0.0;
  double mean_stops = 0.0;
  double median_ms = 0.0;  ///< per trial, the engine-in-the-loop run
};

/// Runs the protocol on each map; `progress(done, total)` after every trial.
std::vector<EngineDisambiguationResult> run_engine_disambiguation(
    const std::vector<EvalMap>& maps, const SonarRing& ring,
    const EngineDisambiguationOptions& options, const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
