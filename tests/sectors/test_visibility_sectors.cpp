// Tests of engine/src/sectors/visibility_sectors.cpp (seed 000): the sectors of hand-checkable
// rooms and N_min (eqs. 10-11).
#include "gridloc/engine/sectors/visibility_sectors.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(VisibilitySectors, ARectangleIsOneSector) {
  const PolygonMap m = make_polygon_map({{0, 0}, {6, 0}, {6, 4}, {0, 4}}, {});
  const SectorMap s = compute_sectors(m);
  ASSERT_EQ(s.sectors.size(), 1u);
  // Four corners (M) and four walls seen square on (m), from east counter-clockwise.
  EXPECT_TRUE(cyclic_equal(s.sectors[0].label, "mMmMmMmM")) << s.sectors[0].label;
  EXPECT_EQ(s.sectors[0].visible.size(), 4u);
  EXPECT_FALSE(s.sectors[0].ambiguous);
  EXPECT_NEAR(s.sectors[0].area_m2, 24.0, 1e-9);
  EXPECT_EQ(s.sector_at({3, 2}), 0);
  EXPECT_EQ(s.sector_at({7, 2}), -1);
}

TEST(VisibilitySectors, AnLShapedRoomHasTheFiveSectorsOfItsReflexCorner) {
  // The reflex corner (3, 3) cuts the L along its two walls extended (x = 3 and y = 3) and
  // along the lines from the far corners (7, 0) and (0, 6) through it: the corner square,
  // and each arm split in two, where the other arm's far corner is or is not in view.
  const PolygonMap m = make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}}, {});
  const SectorMap s = compute_sectors(m);
  ASSERT_EQ(s.sectors.size(), 5u);
  const int square = s.sector_at({1.5, 1.5});
  const int east_near = s.sector_at({3.5, 2.5}), east_far = s.sector_at({6.5, 0.5});
  const int north_near = s.sector_at({2.5, 3.5}), north_far = s.sector_at({0.5, 5.5});
  EXPECT_EQ(s.sectors[square].visible.size(), 6u);  // sees every vertex
  for (int a : {square, east_near, east_far, north_near, north_far}) {
    for (int b : {square, east_near, east_far, north_near, north_far}) {
      if (a != b) {
        EXPECT_NE(s.sectors[a].label, s.sectors[b].label);
      }
    }
  }
  // The far part of the east arm does not see (0, 6): the line (0, 6)-(3, 3) meets y = 0 at
  // x = 6 (x + y = 6), so (6.5, 0.5) lies beyond it and (4, 1) does not.
  const auto sees = [&](int sector, int vertex) {
    const auto& v = s.sectors[sector].visible;
    return std::find(v.begin(), v.end(), vertex) != v.end();
  };
  int corner06 = -1;
  for (std::size_t k = 0; k < s.vertices.size(); ++k) {
    if (s.vertices[k] == Eigen::Vector2d(0, 6)) corner06 = static_cast<int>(k);
  }
  ASSERT_GE(corner06, 0);
  EXPECT_FALSE(sees(east_far, corner06));
  EXPECT_TRUE(sees(s.sector_at({4, 1}), corner06));
  // The scan label from the middle of a sector is the sector's label turned.
  const ScanLabelOptions exact{0.3, 0.15, 1, 0.05};
  for (int sector : {square, east_near, north_far}) {
    const Eigen::Vector2d p = s.sectors[sector].representative;
    const ScanLabel l = construct_scan_label(polygon_scan(m, {p.x(), p.y(), 1.0}, 3600, 20), exact);
    EXPECT_TRUE(cyclic_equal(l.label, s.sectors[sector].label))
        << l.label << " vs " << s.sectors[sector].label;
  }
}

TEST(VisibilitySectors, MinimumReadingsOfASquareRoom) {
  // A 4 m square, clearance 0.97 m: the robot stands in [0.975, 3.025]^2 (cell centres at
  // 5 cm). The smallest angle a wall subtends is at a corner of that square, seeing the far
  // wall: atan(0.975 / 3.025) + 45 deg = 62.866 deg = 1.09722 rad. Eq. (10): 6 pi / alpha =
  // 17.18 -> 18 readings; eq. (11): 4 pi / alpha = 11.45 -> 12.
  const PolygonMap m = make_polygon_map({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {});
  SectorOptions o;
  o.clearance_m = 0.97;
  const SectorMap s = compute_sectors(m, o);
  ASSERT_EQ(s.sectors.size(), 1u);
  EXPECT_EQ(s.sectors[0].n_min, 18);
  EXPECT_EQ(s.sectors[0].n_min_two, 12);
  EXPECT_EQ(s.n_min_two(), 12);
  SectorOptions bad;
  bad.cell_m = 0.0;
  test::expect_error([&] { compute_sectors(m, bad); }, {"cell_m"});
}

TEST(VisibilitySectors, SamplingGridIsCheckedBeforeItIsAllocated) {
  ResourceLimits wide;
  wide.max_coordinate_m = 1e13;
  const PolygonMap huge =
      make_polygon_map({{0, 0}, {1e12, 0}, {1e12, 1e12}, {0, 1e12}}, {}, 0.05, wide);
  SectorOptions o;
  o.limits = wide;
  test::expect_error([&] { compute_sectors(huge, o); }, {"compute_sectors", "--max-cells"});
  const PolygonMap room = make_polygon_map({{0, 0}, {6, 0}, {6, 4}, {0, 4}}, {});
  o.limits.max_memory_mb = 1;  // 120 x 80 cells of 32 bytes: 0.3 MB fits
  EXPECT_EQ(compute_sectors(room, o).sectors.size(), 1u);
  o.cell_m = 0.01;  // 600 x 400 cells: 7.7 MB does not
  test::expect_error([&] { compute_sectors(room, o); }, {"compute_sectors", "--max-memory-mb"});
}

}  // namespace
}  // namespace gridloc
