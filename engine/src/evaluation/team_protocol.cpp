#include "gridloc/engine/evaluation/team_protocol.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

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

RangeScan simulate_ir(const TeamWorld& world, const Pose2& pose, const TeamSensing& sensing,
                      std::uint64_t seed) {
  IrSensorOptions ir = sensing.ir;
  ir.noise = ir.noise && sensing.noise;
  if (!sensing.noise) ir.smoothing_half_window = 0;  // the thesis filtered real data only
  return world.polygons ? simulate_ir_scan(*world.polygons, pose, ir, seed)
                        : simulate_ir_scan(world.grid, pose, ir, seed);
}

}  // namespace

TeamSimulator::TeamSimulator(const TeamWorld& world, TeamSensing sensing)
    : world_(world), sensing_(std::move(sensing)) {
  validate(sensing_.ir);
  validate(sensing_.features);
  validate(sensing_.candidates);
  validate(sensing_.estimate);
  validate(sensing_.camera);
  if (sensing_.sensor == TeamSensor::Sonar) validate(sensing_.ring);
  engine_ = make_engine(world_, sensing_);
}

TeamSimulator::~TeamSimulator() = default;
TeamSimulator::TeamSimulator(TeamSimulator&&) noexcept = default;

TeamRobot TeamSimulator::robot_from_scan(const RangeScan& scan,
                                         std::vector<ScanFeature>* features) const {
  if (sensing_.sensor == TeamSensor::Ir) {
    std::vector<ScanFeature> found = extract_features(scan, sensing_.features);
    TeamRobot robot{robot_candidates(scan, found, world_.features, sensing_.candidates), scan};
    if (features) *features = std::move(found);
    return robot;
  }
  if (!engine_) throw Error("robot_from_scan: a sonar team takes readings, not scans");
  Observation observation;
  observation.scan = scan;
  const Estimate estimate = engine_->estimate(observation, engine_->global_window(observation),
                                              sensing_.estimate.max_candidates + 1);
  return {estimate_candidates(estimate, sensing_.estimate), {}};
}

TeamRobot TeamSimulator::robot_from_sonar(const std::vector<double>& ranges) const {
  if (sensing_.sensor != TeamSensor::Sonar)
    throw Error("robot_from_sonar: the team's sensor is " + to_string(sensing_.sensor));
  Observation observation;
  observation.ranges = ranges;
  const Estimate estimate = engine_->estimate(observation, engine_->global_window(observation),
                                              sensing_.estimate.max_candidates + 1);
  return {estimate_candidates(estimate, sensing_.estimate), {}};
}

TeamCase TeamSimulator::simulate(const std::vector<Pose2>& poses, std::uint64_t seed) const {
  TeamCase team;
  team.truth = poses;
  for (std::size_t r = 0; r < poses.size(); ++r) {
    const std::uint64_t robot_seed = seed * 7919ull + r + 1;
    if (sensing_.sensor == TeamSensor::Sonar) {
      const SonarSimOptions noise =
          sensing_.noise ? SonarSimOptions::realistic(robot_seed) : SonarSimOptions{};
      team.robots.push_back(
          robot_from_sonar(simulate_sonar(world_.grid, sensing_.ring, poses[r], noise)));
      continue;
    }
    const RangeScan scan =
        sensing_.sensor == TeamSensor::Ir
            ? simulate_ir(world_, poses[r], sensing_, robot_seed)
            : simulate_scan(world_.grid, poses[r], sensing_.laser_beams, sensing_.laser_range_m,
                            sensing_.noise ? sensing_.laser_sigma_m : 0.0, robot_seed);
    std::vector<ScanFeature> features;
    team.robots.push_back(robot_from_scan(scan, &features));
    team.scans.push_back(scan);
    team.features.push_back(std::move(features));
  }
  team.links = measurable_links(poses, world_.features, sensing_.camera,
                                sensing_.noise ? seed * 104729ull + 17 : 0);
  return team;
}

}  // namespace gridloc
