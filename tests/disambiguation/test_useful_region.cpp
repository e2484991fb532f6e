// Seed 002 §IV-D step 6: the useful region of an overlay intersection.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
const PlanarSegment kEdge{{4, 0}, {4, 1}};

TEST(UsefulRegion, UnlimitedRangeHoldsWhatSeesTheEdgeAndNotWhatTheCornerHides) {
  for (const PlanarSegment& edge :
       {kEdge, PlanarSegment{kEdge.b, kEdge.a}}) {  // either orientation
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
  const std::vector<PlanarSegment> edges{{{0, 2}, {0, 0}}, {{6, 0}, {6, 2}}};
  const Region useful = useful_region(room, edges, 1.0);
  EXPECT_TRUE(region_holds(useful, {0.5, 1.0}));
  EXPECT_TRUE(region_holds(useful, {5.5, 1.0}));
  EXPECT_FALSE(region_holds(useful, {3.0, 1.8}));  // beyond range of both
  const Region far = useful_region(room, {edges[1]}, kUnlimitedRange);
  EXPECT_TRUE(region_holds(far, {0.5, 1.9}));
  EXPECT_FALSE(region_holds(far, {2.4, 1.0}));  // right behind the pillar
  EXPECT_FALSE(region_holds(far, {3.0, 1.0}));  // in the pillar
}

/// Whether p sees some point of the edge no farther than `range`: brute force over 400 points
/// along it and the edge-rectangle's width.
bool sees_edge(const Area& area, const Eigen::Vector2d& p, const PlanarSegment& edge,
               double range) {
  const Eigen::Vector2d along = (edge.b - edge.a).normalized();
  const double off_line = std::abs(test::cross2(along, p - edge.a));
  if (off_line > range + 1e-6) return false;
  for (int k = 0; k <= 400; ++k) {
    const Eigen::Vector2d q = edge.a + (k / 400.0) * (edge.b - edge.a);
    const double length = (q - p).norm();
    if (test::cast_ray(area, p, (q - p) / length) >= length - 1e-6) return true;
  }
  return false;
}

// Soundness of the inner approximation on random star and rectilinear rooms: every point of U lies
// in oi, within range of the edge's line, and sees the edge; and U is not empty.
TEST(UsefulRegion, EveryPointOfTheRegionSeesAnInternalEdge) {
  std::mt19937 rng(9002);
  for (int room = 0; room < 8; ++room) {
    const Area oi = room < 4 ? test::random_star_room(rng) : test::random_rectilinear_room(rng, 12);
    const std::size_t i = test::uniform_int(rng, 0, static_cast<int>(oi.outer.size()) - 1);
    const PlanarSegment edge{oi.outer[i], oi.outer[(i + 1) % oi.outer.size()]};
    const double range = room % 2 ? kUnlimitedRange : test::uniform_real(rng, 0.5, 3.0);
    const Region useful = useful_region(oi, {edge}, range);
    ASSERT_FALSE(useful.empty());
    int held = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const Eigen::Vector2d p =
          room < 4 ? Eigen::Vector2d(test::uniform_real(rng, -5, 5), test::uniform_real(rng, -5, 5))
                   : Eigen::Vector2d(test::uniform_real(rng, 0, 12), test::uniform_real(rng, 0, 8));
      if (!region_holds(useful, p)) continue;
      ++held;
      EXPECT_TRUE(test::strictly_inside(oi, p)) << p.transpose();
      EXPECT_TRUE(sees_edge(oi, p, edge, range)) << "room " << room << " at " << p.transpose();
    }
    EXPECT_GT(held, 0);
  }
}

TEST(UsefulRegion, BadInputThrows) {
  EXPECT_THROW(useful_region(kRoom, {kEdge}, 0.0), Error);
  EXPECT_THROW(useful_region(kRoom, {kEdge}, 1.0, 0), Error);
  EXPECT_THROW(useful_region(kRoom, {PlanarSegment{{2, 2}, {3, 3}}}, 1.0), Error);
  EXPECT_TRUE(useful_region(kRoom, {}, 1.0).empty());
}

}  // namespace
}  // namespace gridloc
