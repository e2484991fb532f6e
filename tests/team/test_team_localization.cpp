// The team solver on hand-made candidates: the chain, the checks by surplus links, robots
// placed by links alone, weights, verdicts and swaps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/engine/team/team_localization.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

PoseCandidate at(const Pose2& pose, double weight = 1.0) {
  PoseCandidate candidate;
  candidate.pose = pose;
  candidate.weight = weight;
  return candidate;
}

TeamOptions exact_options() {
  TeamOptions options;
  options.min_agreement = 0.0;  // no scans here
  return options;
}

const std::vector<Pose2> kTruth{{1.0, 1.0, 0.3}, {1.7, 1.3, 2.0}, {1.2, 1.9, -1.0}};

std::vector<VirtualLink> chain_links(const std::vector<Pose2>& poses) {
  std::vector<VirtualLink> links;
  for (std::size_t r = 0; r + 1 < poses.size(); ++r)
    links.push_back(
        measure_link(static_cast<int>(r), static_cast<int>(r + 1), poses[r], poses[r + 1], {}, 0));
  return links;
}

void expect_pose(const Pose2& pose, const Pose2& truth, double tolerance = 1e-9) {
  EXPECT_NEAR(pose.x, truth.x, tolerance);
  EXPECT_NEAR(pose.y, truth.y, tolerance);
  EXPECT_NEAR(normalize_angle(pose.theta - truth.theta), 0.0, tolerance);
}

TEST(TeamLocalization, OneRobotWithOneCandidateIsLocalized) {
  const TeamAnswer answer = localize_team({{{at(kTruth[0])}, {}}}, {}, {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Localized);
  expect_pose(answer.robots[0].pose, kTruth[0]);
}

TEST(TeamLocalization, ARobotsTwinIsRuledOutByItsLinkedNeighbour) {
  // Robot 0 alone: two places; robot 1 has one candidate, which only the truth reaches.
  const Pose2 twin{3.0, 3.0, 0.3 - kPi};
  std::vector<TeamRobot> robots{{{at(kTruth[0]), at(twin)}, {}}, {{at(kTruth[1])}, {}}};
  const TeamAnswer answer =
      localize_team(robots, chain_links({kTruth[0], kTruth[1]}), {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Localized);
  EXPECT_TRUE(answer.unique());
  expect_pose(answer.robots[0].pose, kTruth[0]);
  expect_pose(answer.robots[1].pose, kTruth[1]);
  EXPECT_EQ(answer.links_used, std::vector<int>{0});
}

TEST(TeamLocalization, TwinTeamsStayAmbiguousAndEachRobotNamesItsPlaces) {
  // Every robot's twin turned by pi about (2, 2): the whole team's twin reads the same.
  std::vector<TeamRobot> robots;
  for (const Pose2& truth : kTruth) {
    const Pose2 twin{4.0 - truth.x, 4.0 - truth.y, normalize_angle(truth.theta + kPi)};
    robots.push_back({{at(truth), at(twin)}, {}});
  }
  const TeamAnswer answer = localize_team(robots, chain_links(kTruth), {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Ambiguous);
  ASSERT_EQ(answer.solutions.size(), 2u);
  for (const RobotAnswer& robot : answer.robots) {
    EXPECT_EQ(robot.verdict, Verdict::Ambiguous);
    EXPECT_EQ(robot.places.size(), 2u);
  }
}

TEST(TeamLocalization, ASurplusLinkRulesOutWhatTheTreeAllowed) {
  // Link 1-2 carries no back bearing, so the tree lets robot 2 face either way; the surplus
  // link 0-2 measures both bearings and keeps the truth.
  std::vector<VirtualLink> links = chain_links(kTruth);
  links[1].back_bearing = std::nan("");
  links.push_back(measure_link(0, 2, kTruth[0], kTruth[2], {}, 0));
  const Pose2 turned{kTruth[2].x, kTruth[2].y, kTruth[2].theta + 1.0};
  std::vector<TeamRobot> robots{
      {{at(kTruth[0])}, {}}, {{at(kTruth[1])}, {}}, {{at(turned), at(kTruth[2])}, {}}};
  const TeamAnswer answer = localize_team(robots, links, {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Localized);
  expect_pose(answer.robots[2].pose, kTruth[2]);
  EXPECT_EQ(answer.links_used.size(), 3u);
  links.pop_back();  // without it: two solutions
  EXPECT_EQ(localize_team(robots, links, {}, exact_options()).verdict, Verdict::Ambiguous);
}

TEST(TeamLocalization, ARobotWithoutFeaturesIsPlacedByItsLink) {
  std::vector<TeamRobot> robots{{{at(kTruth[0])}, {}}, {{}, {}}};
  const TeamAnswer answer =
      localize_team(robots, chain_links({kTruth[0], kTruth[1]}), {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Localized);
  expect_pose(answer.robots[1].pose, kTruth[1]);
  // And the other way round: the featureless robot is the link's `from`.
  std::vector<TeamRobot> reversed{{{}, {}}, {{at(kTruth[1])}, {}}};
  const TeamAnswer other =
      localize_team(reversed, chain_links({kTruth[0], kTruth[1]}), {}, exact_options());
  expect_pose(other.robots[0].pose, kTruth[0]);
}

TEST(TeamLocalization, TheHighestTotalWeightWinsAndCloseRivalsMakeItAmbiguous) {
  // Two consistent assignments: the truth (weights 1 + 1) and a twin pair (0.9 + 0.9).
  const Pose2 twin0{3.0, 3.0, kTruth[0].theta}, twin1{3.7, 3.3, kTruth[1].theta};
  std::vector<TeamRobot> robots{{{at(twin0, 0.9), at(kTruth[0], 1.0)}, {}},
                                {{at(kTruth[1], 1.0), at(twin1, 0.9)}, {}}};
  TeamOptions options = exact_options();
  const auto links = chain_links({kTruth[0], kTruth[1]});
  options.rival_ratio = 0.95;  // 1.8 / 2.0 = 0.9: not a rival
  TeamAnswer answer = localize_team(robots, links, {}, options);
  EXPECT_EQ(answer.verdict, Verdict::Localized);
  expect_pose(answer.robots[0].pose, kTruth[0]);
  options.rival_ratio = 0.85;  // now it is
  answer = localize_team(robots, links, {}, options);
  EXPECT_EQ(answer.verdict, Verdict::Ambiguous);
  EXPECT_EQ(answer.solutions.size(), 2u);
}

TEST(TeamLocalization, FeaturesInferredFromAGridNeverClaimAUniqueAnswer) {
  std::vector<TeamRobot> robots{{{at(kTruth[0])}, {}}, {{at(kTruth[1])}, {}}};
  const auto links = chain_links({kTruth[0], kTruth[1]});
  MapFeatures inferred;
  inferred.exact = false;
  // Engine hypotheses (no feature behind them): unique is unique.
  EXPECT_EQ(localize_team(robots, links, inferred, exact_options()).verdict, Verdict::Localized);
  // A feature placement on inferred corners could have missed the true corner.
  robots[0].candidates[0].feature = 0;
  const TeamAnswer answer = localize_team(robots, links, inferred, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Ambiguous);
  EXPECT_EQ(answer.solutions.size(), 1u);
  EXPECT_EQ(answer.robots[0].verdict, Verdict::Ambiguous);
}

TEST(TeamLocalization, SwappedRobotsAreNamed) {
  // Two robots facing each other 0.8 m apart, each with a candidate at the other's place.
  const Pose2 a{1.0, 1.0, 0.0}, b{1.8, 1.0, kPi};
  std::vector<TeamRobot> robots{{{at(a), at(b)}, {}}, {{at(b), at(a)}, {}}};
  const TeamAnswer answer = localize_team(robots, chain_links({a, b}), {}, exact_options());
  EXPECT_EQ(answer.verdict, Verdict::Ambiguous);
  ASSERT_EQ(answer.swaps.size(), 1u);
  EXPECT_EQ(answer.swaps[0], (std::pair<int, int>{0, 1}));
}

TEST(TeamLocalization, NoisyLinksAreAveragedOverTheSurplus) {
  // Three robots, all three links measured with noise: the refit lands within the noise.
  CameraModel camera;
  camera.length_sigma_at_max_m = 0.02;
  std::vector<VirtualLink> links;
  for (auto [i, j] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}})
    links.push_back(measure_link(i, j, kTruth[i], kTruth[j], camera, 11 + i * 3 + j));
  std::vector<TeamRobot> robots;
  for (const Pose2& truth : kTruth) robots.push_back({{at(truth)}, {}});
  TeamOptions options = exact_options();
  options.camera = camera;
  const TeamAnswer answer = localize_team(robots, links, {}, options);
  ASSERT_EQ(answer.verdict, Verdict::Localized);
  for (std::size_t r = 0; r < kTruth.size(); ++r)
    expect_pose(answer.robots[r].pose, kTruth[r], 0.02);
}

TEST(TeamLocalization, RefusesTeamsItCannotSolve) {
  test::expect_error(
      [] {
        localize_team({{{}, {}}}, {}, {}, {});
      },
      {"no robot has a candidate placement"});
  std::vector<TeamRobot> robots{{{at(kTruth[0])}, {}}, {{at(kTruth[1])}, {}}};
  test::expect_error([&] { localize_team(robots, {}, {}, {}); }, {"robot 1", "no link"});
  VirtualLink far = measure_link(0, 1, {0, 0, 0}, {2.0, 0, 0}, {}, 0);
  test::expect_error([&] { localize_team(robots, {far}, {}, {}); },
                     {"link 0-1", "beyond the camera's range"});
}

}  // namespace
}  // namespace gridloc
