#pragma once
/// Team localization simulated and evaluated (seed 003 ch. V, issue 16): each robot's sensing
/// at its true pose (the rotating IR sensor and its features, or a laser or sonar ring through
/// the correlation engine), the links the team can measure, and the protocol of random teams
/// in free space with lines of sight between linked robots.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/team/estimate_candidates.hpp"
#include "gridloc/engine/team/team_localization.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/rotating_ir.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// The map a team localizes on: its walls and corners, the map itself for the sensors (a
/// polygon map exactly when there is one) and its occupancy grid for the engine.
struct TeamWorld {
  std::optional<PolygonMap> polygons;
  OccupancyMap grid;
  MapFeatures features;
};

/// From a polygon map (features exact, grid rasterized at its resolution) or an occupancy map
/// (features from its outline).
TeamWorld make_team_world(const PolygonMap& map, const MapFeatureOptions& options = {});
TeamWorld make_team_world(OccupancyMap map, const MapFeatureOptions& options = {});

enum class TeamSensor { Ir, Laser, Sonar };

/// "ir", "laser", "sonar".
std::string to_string(TeamSensor sensor);
/// Throws gridloc::Error naming the accepted names.
TeamSensor parse_team_sensor(const std::string& name);

struct TeamSensing {
  TeamSensor sensor = TeamSensor::Ir;
  IrSensorOptions ir;
  FeatureOptions features;
  CandidateOptions candidates;
  int laser_beams = 360;
  double laser_range_m = 8.0;
  double laser_sigma_m = 0.01;
  SonarRing ring;  ///< for TeamSensor::Sonar
  EstimateCandidateOptions estimate;
  CameraModel camera;
  /// Sensor and link noise; false: exact readings and links, and no moving average (the
  /// thesis filtered its real scans only: on exact ones it would round the corners).
  bool noise = true;
};

/// The solver's options for a team sensing this way: the camera's, and for the estimator path
/// (laser, sonar) placements as loose as the engine's lattice (5 cm, 3 deg) and rivals down to
/// the candidates' min_score_ratio (a look-alike's score on a rasterized map falls a few per
/// cent short of the truth's).
TeamOptions solver_options(const TeamSensing& sensing);

/// One simulated team.
struct TeamCase {
  std::vector<Pose2> truth;
  std::vector<RangeScan> scans;                    ///< IR and laser; empty for sonar
  std::vector<std::vector<ScanFeature>> features;  ///< IR
  std::vector<TeamRobot> robots;
  std::vector<VirtualLink> links;
};

/// Simulates teams on one world; holds the correlation engine a laser or sonar team needs.
class TeamSimulator {
 public:
  /// Throws gridloc::Error for bad sensing options.
  TeamSimulator(const TeamWorld& world, TeamSensing sensing);
  ~TeamSimulator();
  TeamSimulator(TeamSimulator&&) noexcept;

  /// Each robot's sensing at `poses` and the links they can measure (noise from `seed`).
  TeamCase simulate(const std::vector<Pose2>& poses, std::uint64_t seed) const;
  /// A robot's candidates from a scan (IR: its features; laser: the engine's hypotheses).
  TeamRobot robot_from_scan(const RangeScan& scan, std::vector<ScanFeature>* features) const;
  /// A sonar robot's candidates from its ring's readings.
  TeamRobot robot_from_sonar(const std::vector<double>& ranges) const;

  const TeamWorld& world() const { return world_; }
  const TeamSensing& sensing() const { return sensing_; }

 private:
  const TeamWorld& world_;
  TeamSensing sensing_;
  std::unique_ptr<CorrelationEstimator> engine_;
};

struct TeamProtocolOptions {
  std::vector<int> robots = {1, 2, 3, 4};  ///< team sizes, one configuration each
  int trials = 100;                        ///< per team size
  std::uint64_t seed = 1;
  /// A robot stands at least this far from every wall and from the others (m).
  double clearance_m = 0.08;
  /// Correct: every robot within these of its truth (m, rad).
  double correct_m = 0.10;
  double correct_theta = 0.0872664625997;  ///< 5 deg
  int draw_attempts = 5000;                ///< per robot, before the trial is given up
  TeamOptions team;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const TeamProtocolOptions& options);

/// A random team of `count`: the first robot uniform over the free space, each next one within
/// the camera's range of an earlier one with a line of sight, every robot clear of the walls
/// and the others and (IR) seeing a corner or wall. Throws gridloc::Error when the attempts
/// run out.
std::vector<Pose2> draw_team(const TeamSimulator& simulator, int count,
                             const TeamProtocolOptions& options, std::uint64_t seed);

struct TeamConfiguration {
  int robots = 0;
  int trials = 0;
  double unique_correct_rate = 0.0;  ///< localized, every robot correct
  double ambiguous_rate = 0.0;
  double not_localized_rate = 0.0;
  int wrong_localized = 0;  ///< localized with a robot not correct
  /// Over the localized trials' robots.
  double mean_position_error_m = 0.0;
  double mean_heading_error_deg = 0.0;
  double median_ms = 0.0;  ///< features, candidates and the team solve, per trial
};

/// How a team's answer compares with its truth.
struct TeamOutcome {
  Verdict verdict = Verdict::NotLocalized;
  bool correct = false;
  double max_position_error_m = 0.0, max_heading_error = 0.0;  ///< of the best solution
};
TeamOutcome judge(const TeamAnswer& answer, const std::vector<Pose2>& truth,
                  const TeamProtocolOptions& options);

struct TeamProtocolReport {
  std::vector<TeamConfiguration> overall;                 ///< per team size, over every world
  std::vector<std::vector<TeamConfiguration>> per_world;  ///< [world][team size]
};

/// The protocol: options.trials random teams per size on each world (the same seeds on
/// each); `progress` (may be empty) after each trial with (trials done, trials in all).
TeamProtocolReport run_team_protocol(const std::vector<const TeamSimulator*>& worlds,
                                     const TeamProtocolOptions& options,
                                     const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
