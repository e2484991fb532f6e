// Tests of sensors/src/drive_fusion.cpp: sonar firings of a short drive fused into one
// observation of a re-mounted, virtual ring in the latest pose's frame (issue 13).
#include "gridloc/sensors/drive_fusion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "gridloc/sensors/sonar_model.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const SonarRing& ring() {
  static const SonarRing loaded = load_sonar_ring(test::ring_path());
  return loaded;
}

std::vector<double> ranges_of(double range) {
  return std::vector<double>(ring().sonars.size(), range);
}

/// The world position of a sonar's mount and its axis for a robot at `robot`.
Pose2 mount_in_world(const SonarSpec& spec, const Pose2& robot) {
  return compose(robot, {spec.radius * std::cos(spec.bearing), spec.radius * std::sin(spec.bearing),
                         spec.heading});
}

TEST(DriveFusion, OneFiringIsTheRingItself) {
  std::vector<double> ranges = ranges_of(2.0);
  ranges[3] = 6.0;  // no echo
  const FusedFirings fused = fuse_firings(ring(), {{{1.0, 2.0, 0.3}, ranges}});
  ASSERT_EQ(fused.ring.sonars.size(), ring().sonars.size());
  EXPECT_EQ(fused.firings, 1u);
  EXPECT_EQ(fused.distance_m, 0.0);
  EXPECT_EQ(fused.ranges, ranges);
  EXPECT_TRUE(fused.rejected.empty());
  for (std::size_t i = 0; i < ring().sonars.size(); ++i) {
    EXPECT_NEAR(fused.ring.sonars[i].radius, ring().sonars[i].radius, 1e-12) << i;
    EXPECT_NEAR(std::remainder(fused.ring.sonars[i].bearing - ring().sonars[i].bearing,
                               2 * std::numbers::pi),
                0.0, 1e-12)
        << i;
    EXPECT_NEAR(fused.ring.sonars[i].heading, ring().sonars[i].heading, 1e-12) << i;
  }
  for (double theta : {0.0, 0.4, -2.0}) {
    const SparseLocalGrid alone = rasterize_oriented(ring(), ranges, theta, 0.1);
    const SparseLocalGrid from_fusion = rasterize_oriented(fused.ring, fused.ranges, theta, 0.1);
    EXPECT_EQ(alone.dx, from_fusion.dx) << theta;
    EXPECT_EQ(alone.dy, from_fusion.dy) << theta;
    EXPECT_EQ(alone.value, from_fusion.value) << theta;
  }
}

TEST(DriveFusion, RemountedSonarsKeepTheirConesInTheWorld) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> metres(-3.0, 3.0), turn(-3.1, 3.1);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 past{metres(rng), metres(rng), turn(rng)};
    const Pose2 latest{metres(rng), metres(rng), turn(rng)};
    const Pose2 relative = relative_pose(latest, past);
    for (const SonarSpec& spec : ring().sonars) {
      const Pose2 then = mount_in_world(spec, past);
      const Pose2 now = mount_in_world(remount(spec, relative), latest);
      EXPECT_NEAR(then.x, now.x, 1e-9);
      EXPECT_NEAR(then.y, now.y, 1e-9);
      EXPECT_NEAR(normalize_angle(then.theta - now.theta), 0.0, 1e-9);
    }
  }
}

TEST(DriveFusion, FiringsLineUpOldestFirstWithTheirMasks) {
  std::vector<bool> mask(ring().sonars.size(), false);
  mask[5] = true;
  const std::vector<OdometryFiring> drive = {{{0.0, 0.0, 0.0}, ranges_of(1.0)},
                                             {{0.5, 0.0, 0.0}, ranges_of(2.0), mask}};
  const FusedFirings fused = fuse_firings(ring(), drive);
  const std::size_t n = ring().sonars.size();
  ASSERT_EQ(fused.ranges.size(), 2 * n);
  EXPECT_EQ(fused.ranges.front(), 1.0);
  EXPECT_EQ(fused.ranges.back(), 2.0);
  ASSERT_EQ(fused.rejected.size(), 2 * n);
  for (std::size_t i = 0; i < 2 * n; ++i) EXPECT_EQ(fused.rejected[i], i == n + 5) << i;
  // The older firing's sonars sit half a metre behind the robot now.
  const SonarSpec& moved = fused.ring.sonars[0];
  EXPECT_NEAR(moved.radius * std::cos(moved.bearing),
              ring().sonars[0].radius * std::cos(ring().sonars[0].bearing) - 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(fused.distance_m, 0.5);
  EXPECT_NO_THROW(validate_readings(fused.ring, fused.ranges, fused.rejected));
}

TEST(DriveFusion, TheWindowBoundsDistanceTurnAndCount) {
  std::vector<OdometryFiring> straight;
  for (int k = 0; k < 6; ++k) straight.push_back({{1.0 * k, 0.0, 0.0}, ranges_of(2.0)});
  DriveWindowOptions window;
  window.max_distance_m = 2.5;
  FusedFirings fused = fuse_firings(ring(), straight, window);
  EXPECT_EQ(fused.firings, 3u);
  EXPECT_DOUBLE_EQ(fused.distance_m, 2.0);
  window.max_firings = 2;
  EXPECT_EQ(fuse_firings(ring(), straight, window).firings, 2u);

  std::vector<OdometryFiring> turning;
  for (int k = 0; k < 5; ++k) turning.push_back({{0.0, 0.0, deg2rad(40.0 * k)}, ranges_of(2.0)});
  window = {};
  window.max_turn_rad = deg2rad(90.0);
  fused = fuse_firings(ring(), turning, window);
  EXPECT_EQ(fused.firings, 3u);
  EXPECT_NEAR(fused.turn_rad, deg2rad(80.0), 1e-12);
  EXPECT_EQ(fused.ring.sonars.size(), 3 * ring().sonars.size());
}

TEST(DriveFusion, BadDrivesNameTheFiring) {
  test::expect_error([] { fuse_firings(ring(), {}); }, {"drive", "no firing"});
  std::vector<OdometryFiring> drive = {{{0.0, 0.0, 0.0}, ranges_of(1.0)},
                                       {{0.2, 0.0, 0.0}, std::vector<double>(3, 1.0)}};
  test::expect_error([&] { fuse_firings(ring(), drive); }, {"firing 1", "expected 14 ranges"});
  drive[1].ranges = ranges_of(1.0);
  drive[0].odometry.x = std::nan("");
  test::expect_error([&] { fuse_firings(ring(), drive); }, {"firing 0", "odometry"});
  drive[0].odometry.x = 0.0;
  drive[0].ranges[2] = -1.0;
  test::expect_error([&] { fuse_firings(ring(), drive); }, {"firing 0", "range 2", "negative"});
  DriveWindowOptions window;
  window.max_distance_m = -1.0;
  test::expect_error([&] { fuse_firings(ring(), {drive[1]}, window); }, {"max_distance_m"});
  window = {};
  window.max_firings = 0;
  test::expect_error([&] { fuse_firings(ring(), {drive[1]}, window); }, {"max_firings"});
}

}  // namespace
}  // namespace gridloc
