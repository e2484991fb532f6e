// A team robot's sensing turned into its candidates (see team_sensing.hpp).
#include "gridloc/engine/team/team_sensing.hpp"

#include "gridloc/grids/error.hpp"

namespace gridloc {

TeamWorld make_team_world(const PolygonMap& map, const MapFeatureOptions& options) {
  return {map, rasterize_polygon_map(map), polygon_features(map, options)};
}

TeamWorld make_team_world(OccupancyMap map, const MapFeatureOptions& options) {
  MapFeatures features = occupancy_features(map, options);
  return {std::nullopt, std::move(map), std::move(features)};
}

std::string to_string(TeamSensor sensor) {
  switch (sensor) {
    case TeamSensor::Ir:
      return "ir";
    case TeamSensor::Laser:
      return "laser";
    case TeamSensor::Sonar:
      return "sonar";
  }
  return "ir";
}

TeamSensor parse_team_sensor(const std::string& name) {
  if (name == "ir") return TeamSensor::Ir;
  if (name == "laser") return TeamSensor::Laser;
  if (name == "sonar") return TeamSensor::Sonar;
  throw Error("unknown team sensor '" + name + "' (expected ir, laser or sonar)");
}

TeamOptions solver_options(const TeamSensing& sensing) {
  TeamOptions options;
  options.camera = sensing.camera;
  if (sensing.sensor != TeamSensor::Ir) {
    options.gate.placement_sigma_m = 0.05;
    options.gate.heading_sigma = 0.0523598775598;  // 3 deg
    options.rival_ratio = sensing.estimate.min_score_ratio;
  }
  return options;
}

namespace {

std::unique_ptr<CorrelationEstimator> make_engine(const TeamWorld& world,
                                                  const TeamSensing& sensing) {
  CorrelationOptions options;
  options.hypotheses = sensing.estimate.max_candidates + 1;
  if (sensing.sensor == TeamSensor::Laser) {
    options.reach_m = sensing.laser_range_m;
    return std::make_unique<CorrelationEstimator>(world.grid, options);
  }
  if (sensing.sensor == TeamSensor::Sonar)
    return std::make_unique<CorrelationEstimator>(world.grid, sensing.ring, options);
  return nullptr;
}

}  // namespace

TeamCandidates::TeamCandidates(const TeamWorld& world, TeamSensing sensing)
    : world_(world), sensing_(std::move(sensing)) {
  validate(sensing_.ir);
  validate(sensing_.features);
  validate(sensing_.candidates);
  validate(sensing_.estimate);
  validate(sensing_.camera);
  if (sensing_.sensor == TeamSensor::Sonar) validate(sensing_.ring);
  engine_ = make_engine(world_, sensing_);
}

TeamCandidates::~TeamCandidates() = default;
TeamCandidates::TeamCandidates(TeamCandidates&&) noexcept = default;

TeamRobot TeamCandidates::from_scan(const RangeScan& scan,
                                    std::vector<ScanFeature>* features) const {
  if (sensing_.sensor == TeamSensor::Ir) {
    std::vector<ScanFeature> found = extract_features(scan, sensing_.features);
    TeamRobot robot{robot_candidates(scan, found, world_.features, sensing_.candidates), scan};
    if (features) *features = std::move(found);
    return robot;
  }
  if (sensing_.sensor == TeamSensor::Sonar) {
    throw Error("robot_from_scan: a sonar team takes readings, not scans");
  }
  Observation observation;
  observation.scan = scan;
  return from_engine(observation);
}

TeamRobot TeamCandidates::from_sonar(const std::vector<double>& ranges) const {
  if (sensing_.sensor != TeamSensor::Sonar)
    throw Error("robot_from_sonar: the team's sensor is " + to_string(sensing_.sensor));
  Observation observation;
  observation.ranges = ranges;
  return from_engine(observation);
}

TeamRobot TeamCandidates::from_engine(const Observation& observation) const {
  const Estimate estimate = engine_->estimate(observation, engine_->global_window(observation),
                                              sensing_.estimate.max_candidates + 1);
  return {estimate_candidates(estimate, sensing_.estimate), {}};
}

}  // namespace gridloc
