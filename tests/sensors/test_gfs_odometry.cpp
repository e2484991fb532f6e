// Tests of sensors/src/gfs_odometry.cpp and the slips of odometry_noise.cpp (issue 34): a
// GMapping .gfs file's raw odometry read and paired scan by scan with its corrected log;
// files that are not one, or not of the same run, refused with the line; seeded slips.
#include "gridloc/sensors/gfs_odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "gridloc/sensors/odometry_noise.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

CarmenLog log_of(const std::string& text) {
  std::istringstream in(text);
  return parse_carmen_log(in, "corrected.log");
}

TEST(GfsOdometry, ReadsTheRawOdometryOfEachScanAndPairsIt) {
  test::TempDir dir;
  const std::string gfs =
      dir.write("run.gfs",
                "PARAM delta 0.05\n"
                "ODOM 576.5 0.1 -2.2 1134864629.9\n"
                "LASER_READING 3 1.0 2.5 81.91 576.48 -0.10 -1.49 1134864642.9\n"
                "SM_UPDATE 1 0.15 0.06 0.56 -669.2\n"
                "LASER_READING 3 1.1 2.4 3.0 576.58 -0.33 -0.77 1134864643.5\n");
  const std::vector<GfsScan> scans = load_gfs_scans(gfs);
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].odometry.x, 576.48);
  EXPECT_EQ(scans[1].odometry.theta, -0.77);
  EXPECT_EQ(scans[1].line, 5u);
  const CarmenLog log = log_of(
      "FLASER 3 1.0 2.5 81.91 0.1 0.2 0.5 0.1 0.2 0.5 1.0 pippo 1.0\n"
      "FLASER 3 1.1 2.4 3.0 0.3 0.2 0.6 0.3 0.2 0.6 2.0 pippo 2.0\n");
  const std::vector<Pose2> odometry = scan_odometry_from_gfs(log, scans);
  ASSERT_EQ(odometry.size(), 2u);
  EXPECT_EQ(odometry[1].x, 576.58);
  // Another run: the ranges differ, or the counts.
  const CarmenLog other = log_of(
      "FLASER 3 1.0 2.5 81.91 0.1 0.2 0.5 0.1 0.2 0.5 1.0 pippo 1.0\n"
      "FLASER 3 1.9 2.4 3.0 0.3 0.2 0.6 0.3 0.2 0.6 2.0 pippo 2.0\n");
  test::expect_error([&] { scan_odometry_from_gfs(other, scans); },
                     {"scan 1", ".gfs line 5", "not the same run"});
  const CarmenLog shorter = log_of("FLASER 3 1.0 2.5 81.91 0 0 0 0 0 0 1.0 pippo 1.0\n");
  test::expect_error([&] { scan_odometry_from_gfs(shorter, scans); }, {"2 scans", "the log 1"});
}

TEST(GfsOdometry, MalformedFilesNameTheLine) {
  test::TempDir dir;
  test::expect_error([&] { load_gfs_scans(dir.write("a.gfs", "PARAM x 1\nODOM 1 2 3 4\n")); },
                     {"a.gfs", "no LASER_READING"});
  test::expect_error([&] { load_gfs_scans(dir.write("b.gfs", "LASER_READING 3 1 2 3 4 5\n")); },
                     {"b.gfs:1", "x y theta timestamp"});
  test::expect_error([&] { load_gfs_scans(dir.write("c.gfs", "LASER_READING -2 1\n")); },
                     {"c.gfs:1", "beam count"});
  test::expect_error([&] { load_gfs_scans(dir.write("d.gfs", "LASER_READING 3 1 2\n")); },
                     {"d.gfs:1", "fewer ranges"});
  test::expect_error([&] { load_gfs_scans(dir.file("missing.gfs")); }, {"missing.gfs"});
}

TEST(GfsOdometry, TheSharedCsailRunPairsWithItsCorrectedLog) {
  const std::string gfs = std::string(GRIDLOC_TEST_SHARED_DIR) +
                          "/datasets/xiaofeng419_SLAM-2D-LIDAR-SCAN/csail.corrected.gfs";
  const std::string corrected =
      std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/acschaefer_ple/csail-corrected.log.gz";
  if (!std::filesystem::exists(gfs) || !std::filesystem::exists(corrected)) {
    GTEST_SKIP() << "../shared is absent: " << gfs;
  }
  const CarmenLog log = load_carmen_log(corrected);
  const std::vector<Pose2> odometry = scan_odometry_from_gfs(log, load_gfs_scans(gfs));
  ASSERT_EQ(odometry.size(), 406u);
  // The raw odometry's frame is not the map's: it starts elsewhere.
  EXPECT_GT(std::hypot(odometry[0].x - log.lasers[0].robot_pose.x,
                       odometry[0].y - log.lasers[0].robot_pose.y),
            100.0);
}

TEST(OdometryNoise, SlipsComeSeededAtTheirSizeAndSpacing) {
  std::vector<Pose2> path;
  for (int k = 0; k <= 1000; ++k) path.push_back({0.1 * k, 0.0, 0.0});  // 100 m straight
  OdometryNoise noise;
  noise.frac = 0.0;
  noise.rad_per_m = 0.0;
  noise.slip_every_m = 10.0;
  Rng rng(3), again(3);
  const std::vector<Pose2> odometry = drifting_odometry(path, noise, rng);
  const std::vector<Pose2> same = drifting_odometry(path, noise, again);
  int slips = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    EXPECT_EQ(odometry[k].x, same[k].x);
    const Pose2 step = relative_pose(odometry[k - 1], odometry[k]);
    const double turn = std::abs(normalize_angle(step.theta));
    if (turn > 1e-9) {
      ++slips;
      EXPECT_NEAR(turn, noise.slip_rad, 1e-9);
    }
  }
  EXPECT_GE(slips, 4);  // about 10 over 100 m
  EXPECT_LE(slips, 20);
  noise.slip_m = -1.0;
  test::expect_error([&] { validate(noise); }, {"slips"});
}

}  // namespace
}  // namespace gridloc
