#pragma once
/// What a robot of a team senses and how it becomes the robot's candidate placements (seed
/// 003 ch. V, issue 16): the map the team localizes on, the sensor (the rotating IR sensor and
/// its features, or a laser or sonar ring through the correlation engine), and the team
/// solver's options for that sensing. A robot application turns its own scans or firings into
/// team candidates here; the team protocol (evaluation/team_protocol.hpp) simulates them.
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

/// A team's sensed inputs: each robot's candidates, its scan and features (IR and laser;
/// empty for sonar) and the links the team measured; a simulated team also has its truth.
struct TeamCase {
  std::vector<Pose2> truth;
  std::vector<RangeScan> scans;                    ///< IR and laser; empty for sonar
  std::vector<std::vector<ScanFeature>> features;  ///< IR
  std::vector<TeamRobot> robots;
  std::vector<VirtualLink> links;
};

/// Turns a robot's scan or sonar firing into its candidate placements on one world; holds
/// the correlation engine a laser or sonar team needs.
class TeamCandidates {
 public:
  /// Throws gridloc::Error for bad sensing options. `world` must outlive this.
  TeamCandidates(const TeamWorld& world, TeamSensing sensing);
  ~TeamCandidates();
  TeamCandidates(TeamCandidates&&) noexcept;

  /// A robot's candidates from a scan (IR: its features, returned in `features` when given;
  /// laser: the engine's hypotheses). Throws gridloc::Error for a sonar team.
  TeamRobot from_scan(const RangeScan& scan, std::vector<ScanFeature>* features) const;
  /// A sonar robot's candidates from its ring's readings. Throws gridloc::Error for another
  /// sensor.
  TeamRobot from_sonar(const std::vector<double>& ranges) const;

  const TeamWorld& world() const { return world_; }
  const TeamSensing& sensing() const { return sensing_; }

 private:
  TeamRobot from_engine(const Observation& observation) const;

  const TeamWorld& world_;
  TeamSensing sensing_;
  std::unique_ptr<CorrelationEstimator> engine_;
};

}  // namespace gridloc
