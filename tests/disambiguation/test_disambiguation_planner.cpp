// DisambiguationPlanner (issue 31): what a real chair on an occupancy map asks, from its own
// reading, without the simulators.
#include "gridloc/engine/disambiguation/disambiguation_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const std::string kMaps = GRIDLOC_TEST_MAPS_DIR;

double position_error(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

double heading_error(const Pose2& a, const Pose2& b) {
  return std::abs(normalize_angle(a.theta - b.theta));
}

DisambiguationPlannerOptions fast_options() {
  DisambiguationPlannerOptions options;
  options.planner.points = 40;  // as gridloc disambiguate --points 40
  return options;
}

TEST(DisambiguationPlanner, ATwinRoomGivesBothPlacesAndAStopToTellThemApart) {
  const OccupancyMap map = load_ros_map(kMaps + "/room_symmetric.yaml");
  const SonarRing ring = load_sonar_ring(kMaps + "/sensors/wheelchair_14.yaml");
  const DisambiguationPlanner planner(map, ring, fast_options());
  const Pose2 truth{1.1, 1.76, 1.29};
  Observation reading;
  reading.ranges = simulate_sonar(map, ring, truth);

  const std::vector<Pose2> hypotheses = planner.hypotheses(reading);
  ASSERT_EQ(hypotheses.size(), 2u);  // the pose and its twin turned by 180 degrees
  int near_truth = 0;
  for (const Pose2& pose : hypotheses) {
    EXPECT_TRUE(planner.passable(pose));
    if (position_error(pose, truth) < 0.15 && heading_error(pose, truth) < 0.15) ++near_truth;
  }
  EXPECT_EQ(near_truth, 1);
  EXPECT_NEAR(heading_error(hypotheses[0], hypotheses[1]), std::numbers::pi, 0.2);

  const MinimumDistancePlan plan = planner.next_stop(hypotheses, 1);
  EXPECT_EQ(plan.hypotheses.size(), 2u);
  EXPECT_FALSE(plan.resolved);  // nothing sensed at a stop yet
  EXPECT_LE(plan.stops.size(), 1u);
}

TEST(DisambiguationPlanner, AWallIsNoPlaceToStand) {
  const OccupancyMap map = load_ros_map(kMaps + "/room_symmetric.yaml");
  const SonarRing ring = load_sonar_ring(kMaps + "/sensors/wheelchair_14.yaml");
  const DisambiguationPlanner planner(map, ring, fast_options());
  EXPECT_TRUE(planner.passable({1.1, 1.76, 0.0}));
  EXPECT_FALSE(planner.passable({-5.0, -5.0, 0.0}));  // off the map
  const Pose2 corner = map.geometry.to_world_frame(
      {0.5 * map.geometry.resolution, 0.5 * map.geometry.resolution, 0.0});
  EXPECT_FALSE(planner.passable(corner));  // the outer wall's corner cell
}

TEST(DisambiguationPlanner, BadOptionsAreOneErrorNamingTheField) {
  const OccupancyMap map = load_ros_map(kMaps + "/room_symmetric.yaml");
  const SonarRing ring = load_sonar_ring(kMaps + "/sensors/wheelchair_14.yaml");
  DisambiguationPlannerOptions options = fast_options();
  options.planner.points = 0;
  test::expect_error([&] { DisambiguationPlanner(map, ring, options); }, {"points"});
}

}  // namespace
}  // namespace gridloc
