#pragma once
/// Minimum-distance localization (seed 002 §IV, COL and UAL): while several start hypotheses
/// remain, overlay their maps, sample points of the overlay intersection OI (COL) or of its
/// useful region U (UAL), move to the point of highest Value = info / distance_OI, sense, drop
/// the hypotheses whose prediction disagrees, and start again with the rest.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/disambiguation/planning_space.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// What a point's info is divided by (§V-A): the shortest path inside OI from the start
/// (standard weighted) or from where the robot stands now (hybrid).
enum class DistanceStrategy { Weighted, Hybrid };

struct MinimumDistanceOptions {
  SamplingAlgorithm algorithm = SamplingAlgorithm::Ual;
  DistanceStrategy strategy = DistanceStrategy::Hybrid;
  int points = 250;        ///< random points per round, in [1, 1e6]
  std::uint64_t seed = 1;  ///< of the random points
  /// Seed 002 step 8: rounds of sampling, the points doubled each round, before the robot
  /// gives up for want of a useful point (>= 1); at most 2^22 points a stop in all.
  int rounds = 8;
  int max_stops = 100;  ///< the most stops before giving up (>= 1)
  /// Threads scoring a round's points (OpenMP; the same plan for any number).
  int threads = 1;
  /// Points nearer than this (m, along OI) to where the robot stands are not candidates: a
  /// noisy sensor that ruled nothing out would otherwise sense again on the spot (0: seed
  /// 002's perfect sensor, where that cannot happen).
  double min_travel_m = 0.0;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const MinimumDistanceOptions& options);

/// What the robot learns at a stop.
struct StopReading {
  std::vector<int> consistent;  ///< the hypotheses (indices) still standing
  /// Empty, or per consistent hypothesis its start pose refit so that the robot stands where
  /// the sensing put it (an engine's windowed estimate): odometry error stops growing there.
  std::vector<Pose2> refit;
};

/// What the robot learns at start-frame point `stop` of the `active` hypotheses (indices),
/// having come along `route` (start frame, from the previous stop).
using StopSensing = std::function<StopReading(const Eigen::Vector2d& stop,
                                              const std::vector<Eigen::Vector2d>& route,
                                              const std::vector<int>& active)>;

/// Seed 002's perfect sensor on a polygon map: the robot truly started at `true_start`; a
/// hypothesis survives when its predicted view at the stop is the same as the one sensed.
StopSensing perfect_sensing(const Area& free_world, const Pose2& true_start,
                            const std::vector<Pose2>& hypotheses, double range,
                            double tolerance = 1e-6);

struct LocalizationStop {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< start frame
  /// The way there from the previous stop (or the start), shortest inside OI, start frame.
  std::vector<Eigen::Vector2d> route;
  double route_length = 0.0;
  double info = 0.0;            ///< seed 002's info at the point
  double value = 0.0;           ///< info / distance (per the strategy)
  int sampled = 0;              ///< random points drawn for this stop (every round)
  int useful = 0;               ///< of them, those with info > 0
  bool sampled_useful = false;  ///< UAL drew from U (false: COL, or U came out empty)
  std::vector<int> eliminated;  ///< hypotheses ruled out here (indices)
  /// Every hypothesis's start pose as this stop was planned (refits move them): its route in
  /// the world under hypothesis i is to_world(frame[i], route point).
  std::vector<Pose2> frame;
};

struct MinimumDistancePlan {
  std::vector<Pose2> hypotheses;  ///< as given
  std::vector<Pose2> refit;       ///< the same after every StopReading::refit
  std::vector<LocalizationStop> stops;
  std::vector<int> remaining;  ///< the hypotheses still standing at the end (indices)
  double path_length = 0.0;    ///< the sum of the routes
  bool resolved = false;       ///< exactly one remains
  /// Why the robot stopped: "resolved", "no useful point" (every round of step 8 drew none),
  /// "stop limit", or "nothing consistent" (sensing ruled every hypothesis out).
  std::string ended;
};

/// Runs COL or UAL from the start (the start-frame origin) until one hypothesis remains.
/// Throws gridloc::Error for bad options or no hypothesis.
MinimumDistancePlan localize_with_minimum_travel(const PlanningSpace& space,
                                                 const std::vector<Pose2>& hypotheses,
                                                 const StopSensing& sense,
                                                 const MinimumDistanceOptions& options = {});

/// The points of the whole path: the start, then every route's bends and stops (start frame).
std::vector<Eigen::Vector2d> whole_path(const MinimumDistancePlan& plan);

/// The same path in the world under `hypothesis`, each route under the pose it was planned
/// with (LocalizationStop::frame).
std::vector<Eigen::Vector2d> world_path(const MinimumDistancePlan& plan, int hypothesis);

}  // namespace gridloc
