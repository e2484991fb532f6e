// Tests of sensors/src/free_pose.cpp: free poses for a robot's footprint on a map.
#include "gridloc/sensors/free_pose.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(SampleFreePose, FootprintAndClearanceAreFree) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
    const OccupancyMap map = load_ros_map(test::map_path(name));
    const GridGeometry& g = map.geometry;
    Rng rng(9);
    for (int i = 0; i < 25; ++i) {
      const Pose2 p = sample_free_pose(map, ring, 0.25, rng);
      EXPECT_GT(p.theta, -std::numbers::pi - 1e-12);
      EXPECT_LE(p.theta, std::numbers::pi + 1e-12);
      // Every cell whose centre lies within the 0.25 m clearance of the footprint (a 1.10 x
      // 0.70 m rectangle) is free.
      const double c = std::cos(p.theta), s = std::sin(p.theta);
      for (int iy = 0; iy < g.height; ++iy) {
        for (int ix = 0; ix < g.width; ++ix) {
          const Eigen::Vector2d cc = g.cell_center(ix, iy);
          const Pose2 w = g.to_world_frame({cc.x(), cc.y(), 0.0});
          const double dx = w.x - p.x, dy = w.y - p.y;
          const double fx = c * dx + s * dy, fy = -s * dx + c * dy;
          const double ox = std::max(std::abs(fx) - 0.55, 0.0);
          const double oy = std::max(std::abs(fy) - 0.35, 0.0);
          if (std::hypot(ox, oy) <= 0.25) {
            ASSERT_EQ(map.at(ix, iy), CellState::Free)
                << name << " pose (" << p.x << ", " << p.y << ", " << p.theta << ") cell (" << ix
                << ", " << iy << ")";
          }
        }
      }
    }
  }
}

TEST(SampleFreePose, ThrowsWhenNoPoseFits) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  GridGeometry g;
  g.resolution = 0.1;
  g.width = 8;
  g.height = 8;
  const OccupancyMap tiny(g, CellState::Free);  // 0.8 m square: the 1.1 m chair cannot fit
  Rng rng(1);
  test::expect_error([&] { sample_free_pose(tiny, ring, 0.25, rng); },
                     {"sample_free_pose", "no free pose"});
}

}  // namespace
}  // namespace gridloc
