// Seed 002 §IV-D step 6: the useful region of an overlay intersection.
#include <gtest/gtest.h>

#include "disambiguation/view_cases.hpp"
#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

bool region_holds(const Region& region, const Eigen::Vector2d& p) {
  for (const Area& area : region) {
    if (test::strictly_inside(area, p)) return true;
  }
  return false;
}

// An L-shaped oi: the lower arm [0, 4] x [0, 1], the upper arm [0, 1] x [0, 4]; the internal
// edge is the right end of the lower arm, x = 4, y in [0, 1].
const Area kRoom{{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, {}};
const Segment kEdge{{4, 0}, {4, 1}};

TEST(UsefulRegion, UnlimitedRangeHoldsWhatSeesTheEdgeAndNotWhatTheCornerHides) {
  for (const Segment& edge : {kEdge, Segment{kEdge.b, kEdge.a}}) {  // either orientation
    const Region useful = useful_region(kRoom, {edge}, kUnlimitedRange);
    ASSERT_FALSE(useful.empty());
    EXPECT_TRUE(region_holds(useful, {3.9, 0.5}));
    EXPECT_TRUE(region_holds(useful, {0.5, 0.5}));
    EXPECT_TRUE(region_holds(useful, {0.5, 1.05}));  // sees y <= 0.7 past the corner (1, 1)
    EXPECT_FALSE(region_holds(useful, {0.5, 1.2}));  // would need y <= -0.2
    EXPECT_FALSE(region_holds(useful, {0.5, 3.5}));  // behind the reflex corner (1, 1)
    for (const Area& area : useful) EXPECT_GT(signed_area2(area.outer), 0.0);
  }
}

TEST(UsefulRegion, FiniteRangeKeepsTheBandAlongTheEdge) {
  const Region useful = useful_region(kRoom, {kEdge}, 1.5);
  EXPECT_TRUE(region_holds(useful, {3.9, 0.5}));
  EXPECT_TRUE(region_holds(useful, {2.6, 0.9}));
  EXPECT_FALSE(region_holds(useful, {2.4, 0.5}));  // 1.6 from the edge's line
  EXPECT_FALSE(region_holds(useful, {0.5, 0.5}));
  double size = 0.0;
  for (const Area& area : useful) size += area_size(area);
  // The band [2.5, 4] x [0, 1], less the slivers the samples' chorded disks miss at its far
  // corners (an inner approximation).
  EXPECT_LT(size, 1.5 + 1e-9);
  EXPECT_GT(size, 1.49);
}

TEST(UsefulRegion, TwoEdgesGiveTheUnionAndAHoleBlocksTheView) {
  // A room [0, 6] x [0, 2] with a pillar; internal edges at both ends.
  const Area room{test::rectangle(0, 0, 6, 2),
                  {test::reversed(test::rectangle(2.5, 0.5, 3.5, 1.5))}};
  const std::vector<Segment> edges{{{0, 2}, {0, 0}}, {{6, 0}, {6, 2}}};
  const Region useful = useful_region(room, edges, 1.0);
  EXPECT_TRUE(region_holds(useful, {0.5, 1.0}));
  EXPECT_TRUE(region_holds(useful, {5.5, 1.0}));
  EXPECT_FALSE(region_holds(useful, {3.0, 1.8}));  // beyond range of both
  const Region far = useful_region(room, {edges[1]}, kUnlimitedRange);
  EXPECT_TRUE(region_holds(far, {0.5, 1.9}));
  EXPECT_FALSE(region_holds(far, {2.4, 1.0}));  // right behind the pillar
  EXPECT_FALSE(region_holds(far, {3.0, 1.0}));  // in the pillar
}

TEST(UsefulRegion, BadInputThrows) {
  EXPECT_THROW(useful_region(kRoom, {kEdge}, 0.0), Error);
  EXPECT_THROW(useful_region(kRoom, {kEdge}, 1.0, 0), Error);
  EXPECT_THROW(useful_region(kRoom, {Segment{{2, 2}, {3, 3}}}, 1.0), Error);
  EXPECT_TRUE(useful_region(kRoom, {}, 1.0).empty());
}

}  // namespace
}  // namespace gridloc
