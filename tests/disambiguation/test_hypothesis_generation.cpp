#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"

#include <gtest/gtest.h>

#include "disambiguation/comb_rooms.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

TEST(HypothesisGeneration, FindsEveryEqualRoomWithTheHeadingKnown) {
  for (const double range : {kUnlimitedRange, 1.0}) {
    const std::vector<Pose2> hypotheses =
        start_hypotheses(test::comb_rooms(), {3.5, 0.5, 0.0}, {range, false, 1e-6});
    ASSERT_EQ(hypotheses.size(), 3u) << "range " << range;
    for (int room = 0; room < 3; ++room) {
      EXPECT_NEAR(hypotheses[room].x, 0.5 + 3 * room, 1e-9);
      EXPECT_NEAR(hypotheses[room].y, 0.5, 1e-9);
      EXPECT_EQ(hypotheses[room].theta, 0.0);
    }
    EXPECT_EQ(find_pose(hypotheses, {3.5, 0.5, 0.0}), 1);
  }
}

TEST(HypothesisGeneration, APlaceBesideTheDoorIsUniqueWhenTheRangeReachesTheCorridorEnd) {
  // Left in the corridor, the end wall is seen: only one place matches.
  const std::vector<Pose2> hypotheses =
      start_hypotheses(test::comb_rooms(), {0.4, 3.0, 0.0}, {kUnlimitedRange, false, 1e-6});
  ASSERT_EQ(hypotheses.size(), 1u);
  EXPECT_NEAR(hypotheses[0].x, 0.4, 1e-9);
}

TEST(HypothesisGeneration, UpToRotationKeepsTheTranslatedMatches) {
  const Pose2 start{3.5, 0.5, 0.3};
  const std::vector<Pose2> fixed = start_hypotheses(test::comb_rooms(), start, {1.0, false, 1e-6});
  const std::vector<Pose2> turned = start_hypotheses(test::comb_rooms(), start, {1.0, true, 1e-6});
  EXPECT_EQ(fixed.size(), 3u);
  EXPECT_GE(turned.size(), fixed.size());
  for (const Pose2& pose : fixed) EXPECT_GE(find_pose(turned, pose, 1e-6), 0);
  const RangeView sensed = range_view(test::comb_rooms(), {start.x, start.y}, start.theta, 1.0);
  for (const Pose2& pose : turned) {
    EXPECT_TRUE(
        same_view(range_view(test::comb_rooms(), {pose.x, pose.y}, pose.theta, 1.0), sensed));
  }
}

TEST(HypothesisGeneration, RefusesAViewWithoutAVertexAndAStartOutside) {
  // In the middle of a room with a short range nothing but walls (or nothing) is seen.
  EXPECT_THROW(start_hypotheses(test::comb_rooms(), {1.0, 1.0, 0.0}, {0.5, false, 1e-6}), Error);
  EXPECT_THROW(start_hypotheses(test::comb_rooms(), {2.5, 1.0, 0.0}), Error);  // in the wall
  EXPECT_THROW(start_hypotheses(test::comb_rooms(), {1.0, 1.0, 0.0}, {0.0, false, 1e-6}), Error);
}

}  // namespace
}  // namespace gridloc
