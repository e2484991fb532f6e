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

/// A two-beam scan: one return straight ahead at `ahead` m, one no-return to the left.
RangeScan two_beams(double ahead) {
  RangeScan scan;
  scan.angles = {0.0, 0.5 * std::numbers::pi};
  scan.ranges = {ahead, 5.0};
  scan.max_range = 5.0;
  return scan;
}

TEST(DriveFusion, ScansArePlacedWhereTheirSensorWasRelativeToTheLatestPose) {
  // The robot drove 1 m forward and turned left 90 degrees; the laser sits 0.2 m ahead.
  const std::vector<OdometryScan> drive = {{{0.0, 0.0, 0.0}, two_beams(3.0)},
                                           {{1.0, 0.0, 0.5 * std::numbers::pi}, two_beams(2.0)}};
  const Pose2 mount{0.2, 0.0, 0.0};
  ScanModelOptions hits;
  const FusedScans fused = fuse_scans(drive, mount, hits);
  ASSERT_EQ(fused.scans, 2u);
  EXPECT_NEAR(fused.distance_m, 1.0, 1e-12);
  EXPECT_NEAR(fused.turn_rad, 0.5 * std::numbers::pi, 1e-12);
  ASSERT_EQ(fused.points.hit_count, 2u);  // the no-returns give no hit
  // The first return lies at world (3.2, 0): in the latest frame, 2.2 m to the robot's right.
  EXPECT_NEAR(fused.points.x[0], 0.0, 1e-12);
  EXPECT_NEAR(fused.points.y[0], -2.2, 1e-12);
  EXPECT_NEAR(fused.points.norm[0], 2.2, 1e-12);
  EXPECT_NEAR(fused.points.x[1], 2.2, 1e-12);  // the latest: mount + 2 m ahead
  EXPECT_NEAR(fused.points.y[1], 0.0, 1e-12);
  EXPECT_NEAR(fused.points.max_norm, 2.2, 1e-12);
}

TEST(DriveFusion, FusedScanPointsKeepEveryHitBeforeEveryFreeSample) {
  const std::vector<OdometryScan> drive = {{{0.0, 0.0, 0.0}, two_beams(3.0)},
                                           {{0.5, 0.0, 0.0}, two_beams(2.0)}};
  ScanModelOptions samples;
  samples.model = ScanModel::Samples;
  samples.free_samples = 2;
  const FusedScans fused = fuse_scans(drive, {}, samples);
  ASSERT_EQ(fused.points.hit_count, 2u);
  ASSERT_EQ(fused.points.size(), 2u + 2u * 2u * 2u);  // 2 beams x 2 samples per scan
  for (std::size_t k = 0; k < fused.points.size(); ++k) {
    EXPECT_EQ(fused.points.weight[k] > 0.0f, k < fused.points.hit_count) << "point " << k;
  }
  EXPECT_NEAR(fused.points.x[0], 2.5, 1e-12);  // the older return, 0.5 m behind now
  EXPECT_NEAR(fused.points.x[1], 2.0, 1e-12);
}

TEST(DriveFusion, TheScanWindowKeepsTheLatestScansWithinItsBounds) {
  std::vector<OdometryScan> drive;
  for (int k = 0; k < 6; ++k) drive.push_back({{0.5 * k, 0.0, 0.0}, two_beams(3.0)});
  DriveWindowOptions window;
  window.max_distance_m = 1.2;
  EXPECT_EQ(fuse_scans(drive, {}, {}, window).scans, 3u);  // 0 m, 0.5 m and 1 m back
  window = {};
  window.max_firings = 2;
  EXPECT_EQ(fuse_scans(drive, {}, {}, window).scans, 2u);
}

TEST(DriveFusion, BadScanDrivesNameTheScan) {
  test::expect_error([] { fuse_scans({}, {}, {}); }, {"drive", "no scan"});
  std::vector<OdometryScan> drive = {{{0.0, 0.0, 0.0}, two_beams(3.0)},
                                     {{0.2, 0.0, 0.0}, two_beams(-1.0)}};
  test::expect_error([&] { fuse_scans(drive, {}, {}); }, {"scan 1", "negative"});
  drive[1].scan = two_beams(1.0);
  drive[0].odometry.theta = std::nan("");
  test::expect_error([&] { fuse_scans(drive, {}, {}); }, {"scan 0", "odometry"});
  drive[0].odometry.theta = 0.0;
  ScanModelOptions rays;
  rays.model = ScanModel::Rays;
  test::expect_error([&] { fuse_scans(drive, {}, rays); }, {"ray model"});
}

}  // namespace
}  // namespace gridloc
