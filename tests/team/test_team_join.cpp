// Joining pairs' solutions into a team's (seed 003 ch. IV C, Table I) and choosing the links.
#include <gtest/gtest.h>

#include "gridloc/engine/team/team_localization.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using Pair = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

LinkSolutions pair_list(int from, int to, const std::vector<Pair>& locations) {
  LinkSolutions link{from, to, {}};
  for (const auto& [a, b] : locations) {
    PairSolution solution;
    solution.from = {a.x(), a.y(), 0.0};
    solution.to = {b.x(), b.y(), 0.0};
    link.solutions.push_back(solution);
  }
  return link;
}

/// Table I: possible locations of a 4-robot system, pair by pair.
std::vector<LinkSolutions> table_one() {
  using V = Eigen::Vector2d;
  return {
      pair_list(0, 1,
                {{V(1, 1), V(4, 4)}, {V(1, 12), V(4, 7)}, {V(4, 1), V(1, 4)}, {V(4, 12), V(1, 7)}}),
      pair_list(1, 2, {{V(4, 4), V(3, 11)}, {V(4, 7), V(1, 11)}, {V(7, 8), V(4, 13)}}),
      pair_list(2, 3, {{V(3, 2), V(1, 8)}, {V(9, 7), V(3, 10)}, {V(3, 11), V(1, 11)}})};
}

void expect_at(const Pose2& pose, double x, double y) {
  EXPECT_NEAR(pose.x, x, 1e-12);
  EXPECT_NEAR(pose.y, y, 1e-12);
}

TEST(TeamJoin, TableOneThreeRobotsLeaveTheThesisTwoSets) {
  auto chain = table_one();
  chain.pop_back();
  const auto solutions = join_pair_solutions(3, chain, 0.01, 0.01, 1000);
  ASSERT_EQ(solutions.size(), 2u);
  expect_at(solutions[0].poses[0], 1, 1);
  expect_at(solutions[0].poses[1], 4, 4);
  expect_at(solutions[0].poses[2], 3, 11);
  expect_at(solutions[1].poses[0], 1, 12);
  expect_at(solutions[1].poses[1], 4, 7);
  expect_at(solutions[1].poses[2], 1, 11);
}

TEST(TeamJoin, TableOneFourRobotsHaveTheThesisSolution) {
  const auto solutions = join_pair_solutions(4, table_one(), 0.01, 0.01, 1000);
  ASSERT_EQ(solutions.size(), 1u);
  expect_at(solutions[0].poses[0], 1, 1);
  expect_at(solutions[0].poses[1], 4, 4);
  expect_at(solutions[0].poses[2], 3, 11);
  expect_at(solutions[0].poses[3], 1, 11);
}

TEST(TeamJoin, JoinsALinkWhoseSharedRobotIsItsSecond) {
  // Robot 2 placed first (link 2-1), then link 0-1 shares robot 1 as its `to`.
  using V = Eigen::Vector2d;
  const std::vector<LinkSolutions> chain{pair_list(2, 1, {{V(3, 11), V(4, 4)}}),
                                         pair_list(0, 1, {{V(1, 1), V(4, 4)}, {V(9, 9), V(5, 5)}})};
  const auto solutions = join_pair_solutions(3, chain, 0.01, 0.01, 1000);
  ASSERT_EQ(solutions.size(), 1u);
  expect_at(solutions[0].poses[0], 1, 1);
}

TEST(TeamJoin, AFixedPairPinsASlidingOne) {
  using V = Eigen::Vector2d;
  auto first = pair_list(0, 1, {{V(0, 0), V(0, 1)}});
  first.solutions[0].slide = Slide{V(1, 0), 2.0};  // both may slide 2 m along +x
  const auto second = pair_list(1, 2, {{V(1.5, 1), V(1.5, 2)}});
  const auto solutions = join_pair_solutions(3, {first, second}, 0.01, 0.01, 1000);
  ASSERT_EQ(solutions.size(), 1u);
  EXPECT_FALSE(solutions[0].slide.moving());
  expect_at(solutions[0].poses[0], 1.5, 0);
  expect_at(solutions[0].poses[2], 1.5, 2);
}

TEST(TeamJoin, ParallelSlidesKeepTheirOverlap) {
  using V = Eigen::Vector2d;
  auto first = pair_list(0, 1, {{V(0, 0), V(0, 1)}});
  first.solutions[0].slide = Slide{V(1, 0), 2.0};
  auto second = pair_list(1, 2, {{V(1, 1), V(1, 2)}});
  second.solutions[0].slide = Slide{V(1, 0), 3.0};
  const auto solutions = join_pair_solutions(3, {first, second}, 0.01, 0.01, 1000);
  ASSERT_EQ(solutions.size(), 1u);
  EXPECT_NEAR(solutions[0].slide.length, 1.0, 1e-12);
  expect_at(solutions[0].poses[0], 1, 0);
  expect_at(solutions[0].poses[2], 1, 2);
}

TEST(TeamJoin, StopsAtTheirLimitAndSaysSo) {
  bool truncated = false;
  EXPECT_TRUE(join_pair_solutions(4, table_one(), 1e9, 10.0, 3, &truncated).size() <= 3u);
  EXPECT_TRUE(truncated);
}

VirtualLink link_of(int from, int to, double length) {
  VirtualLink link;
  link.from = from;
  link.to = to;
  link.length_m = length;
  return link;
}

TEST(ChooseLinks, ShortestMaximumLinkTreeInJoinOrder) {
  // 0-1 0.9, 1-2 0.3, 0-2 0.5, 2-3 0.8, 1-3 1.0: the tree is 1-2, 0-2, 2-3.
  const std::vector<VirtualLink> links{link_of(0, 1, 0.9), link_of(1, 2, 0.3), link_of(0, 2, 0.5),
                                       link_of(2, 3, 0.8), link_of(1, 3, 1.0)};
  EXPECT_EQ(choose_links(4, links), (std::vector<int>{1, 2, 3}));
}

TEST(ChooseLinks, NamesARobotWithoutLink) {
  test::expect_error([] { choose_links(3, {link_of(0, 1, 0.5)}); },
                     {"robot 2", "no link", "line of sight"});
}

}  // namespace
}  // namespace gridloc
