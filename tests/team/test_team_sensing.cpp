// TeamCandidates (issue 31): a robot's own laser scan or sonar firing to its team candidates,
// without the team protocol's simulator.
#include "gridloc/engine/team/team_sensing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const std::string kTRoomLab = std::string(GRIDLOC_TEST_MAPS_DIR) + "/polygons/t_room_lab.yaml";

bool has_candidate_near(const TeamRobot& robot, const Pose2& truth) {
  for (const PoseCandidate& candidate : robot.candidates) {
    const Pose2& pose = candidate.pose;
    if (std::hypot(pose.x - truth.x, pose.y - truth.y) < 0.1 &&
        std::abs(normalize_angle(pose.theta - truth.theta)) < 0.1) {
      return true;
    }
  }
  return false;
}

TEST(TeamCandidates, ALaserScanGivesACandidateAtItsPose) {
  const TeamWorld world = make_team_world(load_polygon_map(kTRoomLab));
  TeamSensing sensing;
  sensing.sensor = TeamSensor::Laser;
  const TeamCandidates candidates(world, sensing);
  const Pose2 truth{0.65, 0.85, 3.14159265};
  const RangeScan scan =
      simulate_scan(world.grid, truth, sensing.laser_beams, sensing.laser_range_m, 0.0, 1);
  const TeamRobot robot = candidates.from_scan(scan, nullptr);
  ASSERT_FALSE(robot.candidates.empty());
  EXPECT_TRUE(has_candidate_near(robot, truth));
}

TEST(TeamCandidates, EachSensorTakesItsOwnReadings) {
  const TeamWorld world = make_team_world(load_polygon_map(kTRoomLab));
  TeamSensing laser;
  laser.sensor = TeamSensor::Laser;
  test::expect_error(
      [&] {
        TeamCandidates(world, laser).from_sonar({1.0, 2.0});
      },
      {"sensor is laser"});
  TeamSensing sonar;
  sonar.sensor = TeamSensor::Sonar;
  sonar.ring = load_sonar_ring(std::string(GRIDLOC_TEST_MAPS_DIR) + "/sensors/wheelchair_14.yaml");
  const RangeScan scan = simulate_scan(world.grid, {0.65, 0.85, 0.0}, 360, 8.0, 0.0, 1);
  test::expect_error([&] { TeamCandidates(world, sonar).from_scan(scan, nullptr); },
                     {"a sonar team takes readings"});
}

}  // namespace
}  // namespace gridloc
