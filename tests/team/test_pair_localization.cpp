// Pair localization (seed 003 ch. III B): pairs of candidates that agree with the link.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/engine/team/pair_localization.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

PoseCandidate point(double x, double y, double theta) {
  PoseCandidate candidate;
  candidate.pose = {x, y, theta};
  return candidate;
}

PoseCandidate segment(double x, double y, double theta, Eigen::Vector2d along, double length) {
  PoseCandidate candidate = point(x, y, theta);
  candidate.along = along.normalized();
  candidate.length = length;
  return candidate;
}

TEST(PairLocalization, KeepsTheCandidatesTheLinkJoins) {
  const Pose2 a{1.0, 1.0, 0.5}, b{1.6, 1.4, 2.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  const std::vector<PoseCandidate> first{point(3, 3, 0.5), point(a.x, a.y, a.theta)};
  const std::vector<PoseCandidate> second{point(b.x, b.y, b.theta), point(3.6, 3.4, 0.0)};
  const auto solutions = localize_pair(first, second, link, {}, {});
  ASSERT_EQ(solutions.size(), 1u);
  EXPECT_EQ(solutions[0].candidate_from, 1);
  EXPECT_EQ(solutions[0].candidate_to, 0);
  EXPECT_NEAR(solutions[0].residual_m, 0.0, 1e-12);
}

TEST(PairLocalization, TwinPlacementsBothAgree) {
  // The second robot's twin at the first's twin, both turned by pi about (2, 2).
  const Pose2 a{1.0, 1.0, 0.5}, b{1.6, 1.4, 2.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  const std::vector<PoseCandidate> first{point(a.x, a.y, a.theta), point(3.0, 3.0, 0.5 - kPi)};
  const std::vector<PoseCandidate> second{point(b.x, b.y, b.theta), point(2.4, 2.6, 2.0 - kPi)};
  EXPECT_EQ(localize_pair(first, second, link, {}, {}).size(), 2u);
}

TEST(PairLocalization, RelativeHeadingRejectsATurnedCandidate) {
  const Pose2 a{1.0, 1.0, 0.5}, b{1.6, 1.4, 2.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  const std::vector<PoseCandidate> second{point(b.x, b.y, b.theta + 0.5)};
  EXPECT_TRUE(localize_pair({point(a.x, a.y, a.theta)}, second, link, {}, {}).empty());
  VirtualLink bearing_only = link;
  bearing_only.back_bearing = std::nan("");
  EXPECT_EQ(localize_pair({point(a.x, a.y, a.theta)}, second, bearing_only, {}, {}).size(), 1u);
}

TEST(PairLocalization, AWallBetweenThemRejectsThePair) {
  const Pose2 a{1.0, 1.0, 0.0}, b{1.8, 1.0, 0.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  MapFeatures map;
  map.walls.push_back({{1.4, 0.0}, {1.4, 2.0}});
  EXPECT_TRUE(localize_pair({point(1, 1, 0)}, {point(1.8, 1, 0)}, link, map, {}).empty());
}

TEST(PairLocalization, ACornerPinsTheRobotAlongAWall) {
  // Robot 2 saw only a wall: it may stand anywhere from (0.2, 0.5) to (0.2, 3.5), heading 0.
  const Pose2 a{1.0, 1.0, 0.3}, b{0.2, 1.7, 0.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  const auto solutions = localize_pair({point(a.x, a.y, a.theta)},
                                       {segment(0.2, 0.5, 0.0, {0, 1}, 3.0)}, link, {}, {});
  ASSERT_EQ(solutions.size(), 1u);
  EXPECT_NEAR(solutions[0].to.x, 0.2, 1e-12);
  EXPECT_NEAR(solutions[0].to.y, 1.7, 1e-12);
  EXPECT_FALSE(solutions[0].slide.moving());
}

TEST(PairLocalization, AWallTooShortForThePlacementMisses) {
  const Pose2 a{1.0, 1.0, 0.3}, b{0.2, 1.7, 0.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  EXPECT_TRUE(
      localize_pair({point(a.x, a.y, a.theta)}, {segment(0.2, 0.5, 0.0, {0, 1}, 0.9)}, link, {}, {})
          .empty());
}

TEST(PairLocalization, TwoRobotsAlongParallelWallsSlide) {
  // Both saw one wall each, the walls parallel: the pair slides along the overlap.
  const Pose2 a{0.2, 1.0, 0.0}, b{1.0, 1.3, kPi};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  const auto sliding = localize_pair({segment(0.2, 0.5, 0.0, {0, 1}, 2.0)},
                                     {segment(1.0, 3.0, kPi, {0, -1}, 2.0)}, link, {}, {});
  ASSERT_EQ(sliding.size(), 1u);
  ASSERT_TRUE(sliding[0].slide.moving());
  // from's y in [0.5, 2.5] and to's y = from's y + 0.3 in [1.0, 3.0]: y in [0.7, 2.5].
  EXPECT_NEAR(sliding[0].from.y, 0.7, 1e-9);
  EXPECT_NEAR(sliding[0].slide.length, 1.8, 1e-9);
}

}  // namespace
}  // namespace gridloc
