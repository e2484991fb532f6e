// Virtual links: what the camera measures, its errors, its range and line of sight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/engine/team/virtual_link.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

MapFeatures wall_between() {  // one wall from (0.5, -1) to (0.5, 1)
  MapFeatures map;
  map.walls.push_back({{0.5, -1.0}, {0.5, 1.0}});
  return map;
}

TEST(VirtualLink, NoiseFreeLinkReproducesTheSecondPose) {
  const Pose2 a{0.2, 0.3, 0.5}, b{0.9, 0.1, -2.0};
  const VirtualLink link = measure_link(0, 1, a, b, {}, 0);
  EXPECT_NEAR(link.length_m, std::hypot(0.7, 0.2), 1e-12);
  const Eigen::Vector2d p = linked_position(link, a);
  EXPECT_NEAR(p.x(), b.x, 1e-12);
  EXPECT_NEAR(p.y(), b.y, 1e-12);
  EXPECT_NEAR(normalize_angle(linked_heading(link, a.theta) - b.theta), 0.0, 1e-12);
}

TEST(VirtualLink, WithoutBackBearingTheHeadingIsUnknown) {
  VirtualLink link = measure_link(0, 1, {0, 0, 0}, {1, 0, 0}, {}, 0);
  link.back_bearing = std::nan("");
  EXPECT_TRUE(std::isnan(linked_heading(link, 0.0)));
}

TEST(VirtualLink, LengthErrorGrowsWithTheSquareOfTheLength) {
  CameraModel camera;
  camera.length_sigma_at_max_m = 0.04;
  EXPECT_NEAR(length_sigma(camera, camera.max_range_m), 0.04, 1e-15);
  EXPECT_NEAR(length_sigma(camera, camera.max_range_m / 2), 0.01, 1e-15);
}

TEST(VirtualLink, NoisyLinksSpreadAsTheCameraModelSays) {
  CameraModel camera;
  camera.length_sigma_at_max_m = 0.05;
  double sum = 0, sum2 = 0;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    const double error = measure_link(0, 1, {0, 0, 0}, {1.1, 0, 0}, camera, 100 + k).length_m - 1.1;
    sum += error;
    sum2 += error * error;
  }
  const double sigma = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_NEAR(sigma, 0.05, 0.005);
}

TEST(VirtualLink, RefusesLinksTheCameraCannotMeasure) {
  const CameraModel camera;
  VirtualLink link = measure_link(0, 1, {0, 0, 0}, {1.4, 0, 0}, camera, 0);
  test::expect_error([&] { validate(link, 2, camera); },
                     {"link 0-1", "1.4 m", "beyond the camera's range", "1.1 m"});
  link.length_m = 0.5;
  link.to = 0;
  test::expect_error([&] { validate(link, 2, camera); }, {"link 0-0", "two different robots"});
  link.to = 5;
  test::expect_error([&] { validate(link, 2, camera); }, {"link 0-5", "out of range"});
  link.to = 1;
  link.bearing = std::nan("");
  test::expect_error([&] { validate(link, 2, camera); }, {"bearing"});
}

TEST(VirtualLink, LineOfSightIsBlockedByAWall) {
  const MapFeatures map = wall_between();
  EXPECT_FALSE(line_of_sight(map, {0, 0}, {1, 0}));
  EXPECT_TRUE(line_of_sight(map, {0, 0}, {0.4, 0.5}));
  EXPECT_TRUE(line_of_sight(map, {0, 1.5}, {1, 1.5}));
}

TEST(VirtualLink, MeasurableLinksNeedRangeAndSight) {
  const std::vector<Pose2> poses{{0, 0, 0}, {1, 0, 0}, {0, 0.8, 0}, {0, 2.5, 0}};
  const auto links = measurable_links(poses, wall_between(), {}, 0);
  // 0-1 blocked by the wall, 0-3 and 2-3 beyond range... 2-3 is 1.7 m: also out.
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(links[0].from, 0);
  EXPECT_EQ(links[0].to, 2);
}

}  // namespace
}  // namespace gridloc
