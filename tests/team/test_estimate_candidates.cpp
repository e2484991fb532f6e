// The team solver on the engine's own hypotheses (beyond seed 003): a laser robot in the
// symmetric room has two places; linked robots keep exactly the team's two (the room turned
// by 180 degrees is itself, so the team turned with it reads the same), in an asymmetric room
// none.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/engine/evaluation/team_protocol.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

TeamWorld polygon_world(const std::string& name) {
  return make_team_world(
      load_polygon_map(std::string(GRIDLOC_TEST_MAPS_DIR) + "/polygons/" + name + ".yaml"));
}

TeamSensing laser() {
  TeamSensing sensing;
  sensing.sensor = TeamSensor::Laser;
  sensing.laser_range_m = 8.0;
  return sensing;
}

TeamOptions estimator_options() {
  TeamOptions options;
  options.gate.placement_sigma_m = 0.05;  // the engine's lattice, not a corner fit
  options.gate.heading_sigma = 3.0 * kPi / 180.0;
  options.rival_ratio = 0.8;  // a rasterized twin scores ~0.9 of the truth
  return options;
}

double distance(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

TEST(EstimateCandidates, WeightsAreScoresOverTheWinnersAndWeakOnesAreLeftOut) {
  Estimate estimate;
  estimate.verdict = Verdict::Ambiguous;
  estimate.pose = {1.01, 2.0, 0.1};
  estimate.alternatives = {{{1.0, 2.0, 0.1}, 10.0}, {{5.0, 2.0, 3.0}, 9.5}, {{3.0, 1.0, 0.0}, 7.0}};
  const auto candidates = estimate_candidates(estimate);
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].pose.x, 1.01);  // the refined winner
  EXPECT_DOUBLE_EQ(candidates[1].weight, 0.95);
  EstimateCandidateOptions one;
  one.max_candidates = 1;  // two alternatives within the ratio: crowded, no candidate
  EXPECT_TRUE(estimate_candidates(estimate, one).empty());
  one.max_candidates = 2;
  EXPECT_EQ(estimate_candidates(estimate, one).size(), 2u);
  estimate.verdict = Verdict::NotLocalized;  // not believed: no candidate
  EXPECT_TRUE(estimate_candidates(estimate).empty());
  one.skip_not_localized = false;
  EXPECT_EQ(estimate_candidates(estimate, one).size(), 2u);
  one.min_score_ratio = 0.0;
  test::expect_error([&] { estimate_candidates(estimate, one); }, {"min_score_ratio"});
}

TEST(EstimateCandidates, TheSymmetricRoomsTwinStaysForTheTeamTurnedWithIt) {
  const TeamWorld world = polygon_world("room_symmetric");
  const TeamSimulator simulator(world, laser());
  const std::vector<Pose2> truth{{1.2, 1.0, 0.4}, {1.9, 1.5, 2.0}};
  const TeamCase team = simulator.simulate(truth, 3);
  // Alone, each robot has its place and the place turned by 180 degrees about the centre.
  const TeamAnswer alone = localize_team({team.robots[0]}, {}, world.features, estimator_options());
  EXPECT_EQ(alone.verdict, Verdict::Ambiguous);
  ASSERT_GE(alone.robots[0].places.size(), 2u);
  const TeamAnswer linked =
      localize_team(team.robots, team.links, world.features, estimator_options());
  EXPECT_EQ(linked.verdict, Verdict::Ambiguous);
  ASSERT_EQ(linked.solutions.size(), 2u);
  for (int r = 0; r < 2; ++r) {
    const auto& places = linked.robots[r].places;
    ASSERT_EQ(places.size(), 2u);
    const Pose2 twin{6.3 - truth[r].x, 4.3 - truth[r].y, normalize_angle(truth[r].theta + kPi)};
    const bool first_is_truth = distance(places[0], truth[r]) < distance(places[1], truth[r]);
    EXPECT_LT(distance(first_is_truth ? places[0] : places[1], truth[r]), 0.1);
    EXPECT_LT(distance(first_is_truth ? places[1] : places[0], twin), 0.2);  // a lattice pose
  }
}

}  // namespace
}  // namespace gridloc
