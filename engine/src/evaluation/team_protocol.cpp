#include "gridloc/engine/evaluation/team_protocol.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {

namespace {

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
    : candidates_(world, std::move(sensing)) {}

TeamSimulator::TeamSimulator(TeamCandidates candidates) : candidates_(std::move(candidates)) {}

TeamCase TeamSimulator::simulate(const std::vector<Pose2>& poses, std::uint64_t seed) const {
  const TeamWorld& team_world = world();
  const TeamSensing& robot_sensing = sensing();
  TeamCase team;
  team.truth = poses;
  for (std::size_t r = 0; r < poses.size(); ++r) {
    const std::uint64_t robot_seed = seed * 7919ull + r + 1;
    if (robot_sensing.sensor == TeamSensor::Sonar) {
      const SonarSimOptions noise =
          robot_sensing.noise ? SonarSimOptions::realistic(robot_seed) : SonarSimOptions{};
      team.robots.push_back(
          robot_from_sonar(simulate_sonar(team_world.grid, robot_sensing.ring, poses[r], noise)));
      continue;
    }
    const RangeScan scan =
        robot_sensing.sensor == TeamSensor::Ir
            ? simulate_ir(team_world, poses[r], robot_sensing, robot_seed)
            : simulate_scan(team_world.grid, poses[r], robot_sensing.laser_beams,
                            robot_sensing.laser_range_m,
                            robot_sensing.noise ? robot_sensing.laser_sigma_m : 0.0, robot_seed);
    std::vector<ScanFeature> features;
    team.robots.push_back(robot_from_scan(scan, &features));
    team.scans.push_back(scan);
    team.features.push_back(std::move(features));
  }
  team.links = measurable_links(poses, team_world.features, robot_sensing.camera,
                                robot_sensing.noise ? seed * 104729ull + 17 : 0);
  return team;
}

}  // namespace gridloc
