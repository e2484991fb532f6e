// Predicted scans as views (seed 002 §IV-A on grids): symmetric twins share a class, distinct
// places do not; the range limit and the no-return rule; info from the class sizes.
#include "gridloc/engine/disambiguation/grid_views.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "gridloc/engine/disambiguation/grid_overlay.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;

/// The pose turned by 180 degrees about the symmetric room's centre (3.15, 2.15).
Pose2 twin(const Pose2& p) {
  return {6.3 - p.x, 4.3 - p.y, normalize_angle(p.theta + std::numbers::pi)};
}

TEST(ScanClasses, SymmetricTwinsShareAClassAndAnotherPlaceDoesNot) {
  const OccupancyMap map = load_ros_map(test::map_path("room_symmetric"));
  const Pose2 pose{1.3, 1.1, 0.4};
  const Pose2 moved{pose.x + 1.0, pose.y, pose.theta};
  const std::vector<Pose2> hypotheses{pose, twin(pose), moved};
  for (const double range : {4.0, std::numeric_limits<double>::infinity()}) {
    for (const Eigen::Vector2d& r : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.5, -0.3)}) {
      EXPECT_EQ(scan_classes(map, hypotheses, r, range), (std::vector<int>{0, 0, 1}))
          << range << " " << r.transpose();
    }
  }
  EXPECT_NEAR(grid_info(map, hypotheses, {0.0, 0.0}, 4.0), 4.0 / 3.0, 1e-12);
  const std::vector<Pose2> reordered{moved, pose, twin(pose)};
  EXPECT_EQ(scan_classes(map, reordered, {0.0, 0.0}, 4.0), (std::vector<int>{0, 1, 1}));
}

TEST(ScanClasses, BeamsWithoutReturnsAreEqualAndAReturnDiffers) {
  const OccupancyMap map = test::walled_room(80, 80, 0.05, {0.0, 0.0});  // 4 x 4 m
  const std::vector<Pose2> open{{1.5, 1.5, 0.0}, {2.5, 2.0, 1.0}};       // far from every wall
  EXPECT_EQ(scan_classes(map, open, {0.0, 0.0}, 0.3), (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(grid_info(map, open, {0.0, 0.0}, 0.3), 0.0);
  // 0.2 m from the west wall's face, a 0.3 m sensor sees it on about a quarter of the beams
  const std::vector<Pose2> near_wall{{1.5, 1.5, 0.0}, {0.25, 2.0, 0.0}};
  EXPECT_EQ(scan_classes(map, near_wall, {0.0, 0.0}, 0.3), (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(grid_info(map, near_wall, {0.0, 0.0}, 0.3), 1.0);
  ScanEquivalence lenient;
  lenient.share = 0.5;  // now a quarter of the beams is not enough
  EXPECT_EQ(scan_classes(map, near_wall, {0.0, 0.0}, 0.3, lenient), (std::vector<int>{0, 0}));
}

TEST(ScanClasses, ToleranceDecidesSmallShifts) {
  const OccupancyMap map = test::walled_room(80, 80, 0.05, {0.0, 0.0});
  const std::vector<Pose2> shifted{{2.0, 2.0, 0.0}, {2.3, 2.0, 0.0}};
  EXPECT_EQ(scan_classes(map, shifted, {0.0, 0.0}, 10.0), (std::vector<int>{0, 1}));
  ScanEquivalence coarse;
  coarse.tolerance_m = 2.0;
  EXPECT_EQ(scan_classes(map, shifted, {0.0, 0.0}, 10.0, coarse), (std::vector<int>{0, 0}));
}

TEST(ScanClasses, InfoOfDistinctViews) {
  const OccupancyMap map = test::walled_room(80, 80, 0.05, {0.0, 0.0});
  const std::vector<Pose2> three{{0.6, 0.6, 0.0}, {2.0, 2.0, 0.0}, {3.3, 1.0, 0.0}};
  EXPECT_EQ(scan_classes(map, three, {0.0, 0.0}, 10.0), (std::vector<int>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(grid_info(map, three, {0.0, 0.0}, 10.0), 2.0);  // 3 x (1/3)(3 - 1)
  EXPECT_TRUE(scan_classes(map, {}, {0.0, 0.0}, 10.0).empty());
  EXPECT_DOUBLE_EQ(grid_info(map, {}, {0.0, 0.0}, 10.0), 0.0);
}

TEST(ScanClasses, InformationOnlyInTheUsefulRegion) {
  // seed 002 §IV-C step 7: only points that see a landmark within range carry information;
  // on the grid those are U's cells. Two starts 1 m apart in a 3.8 x 2.8 m room, 0.55 m sensor.
  const OccupancyMap map = test::walled_room(40, 30, 0.1, {0.0, 0.0});
  const std::vector<Pose2> hypotheses{{2.0, 1.5, 0.0}, {3.0, 1.5, 0.0}};
  const double range = 0.55;
  const GridOverlay overlay = make_grid_overlay(map, hypotheses, range);
  int informative = 0;
  for (int iy = 0; iy < overlay.grid.height; ++iy) {
    for (int ix = 0; ix < overlay.grid.width; ++ix) {
      const std::size_t i = overlay.grid.index(ix, iy);
      if (!overlay.in_oi[i]) continue;
      const double info = grid_info(map, hypotheses, overlay.cell_center({ix, iy}), range);
      if (info > 0.0) {
        ++informative;
        EXPECT_TRUE(overlay.useful[i]) << ix << " " << iy;
      }
      if (overlay.internal[i]) {
        EXPECT_DOUBLE_EQ(info, 1.0) << ix << " " << iy;  // one wall 5 cm away, the other 1 m
      }
    }
  }
  EXPECT_GE(informative, overlay.internal_count);
}

TEST(ScanClasses, BadInputThrows) {
  const OccupancyMap map = test::walled_room(20, 20, 0.1, {0.0, 0.0});
  const std::vector<Pose2> one{{1.0, 1.0, 0.0}};
  expect_error([&] { scan_classes(map, one, {0.0, 0.0}, 0.0); }, {"range"});
  expect_error([&] { scan_classes(map, one, {std::nan(""), 0.0}, 1.0); }, {"point r"});
  expect_error([&] { scan_classes(OccupancyMap{}, one, {0.0, 0.0}, 1.0); }, {"empty"});
  ScanEquivalence bad;
  bad.beams = 0;
  expect_error([&] { scan_classes(map, one, {0.0, 0.0}, 1.0, bad); }, {"beams", "0"});
  bad = {};
  bad.tolerance_m = -0.1;
  expect_error([&] { scan_classes(map, one, {0.0, 0.0}, 1.0, bad); }, {"tolerance_m"});
  bad = {};
  bad.share = 0.0;
  expect_error([&] { grid_info(map, one, {0.0, 0.0}, 1.0, bad); }, {"share"});
}

}  // namespace
}  // namespace gridloc
