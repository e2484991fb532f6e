// Tests of how precisely a laser Localizer places a tracked place (issue 34): a window's
// position fused with where the odometry carried the place, and the spread a laser's place
// must be within to be `localized`.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "laser_cases.hpp"
#include "test_support.hpp"
#include "tracking_cases.hpp"

namespace gridloc {
namespace {

using test::kRange;
using test::laser;
using test::laser_options;
using test::right;
using test::scan_at;
using test::two_rooms;

// LocalizerOptions::fuse_carried_position: scans with 4 cm of range noise along a drive
// with exact odometry. Each scan's match is a few centimetres off at random; fused with where
// the odometry carried the place, the track's positions are closer to the truth on the
// whole, and every answer stays `localized` and right.
TEST(Tracking, AScansMatchIsFusedWithWhereTheOdometryCarriedThePlace) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 10.55; x += 0.1) path.push_back({x, 5.5, 0.0});
  double error_sum[2] = {0.0, 0.0};
  for (const bool fuse : {false, true}) {
    LocalizerOptions options = laser_options();
    options.fuse_carried_position = fuse;
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    for (std::size_t k = 0; k < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      localizer.add_observation(double(k), simulate_scan(map, path[k], 360, kRange, 0.04, 7 + k));
      const Estimate e = localizer.estimate();
      ASSERT_TRUE(right(e, path[k])) << "fuse " << fuse << " step " << k;
      EXPECT_EQ(e.verdict, Verdict::Localized) << "fuse " << fuse << " step " << k;
      error_sum[fuse] += std::hypot(e.pose.x - path[k].x, e.pose.y - path[k].y);
    }
  }
  EXPECT_LT(error_sum[1], 0.8 * error_sum[0]) << error_sum[1] << " vs " << error_sum[0];
  LocalizerOptions bad = laser_options();
  bad.fused_window_error_m = -0.01;
  test::expect_error([&] { Localizer(map, laser(), bad); }, {"fused_window_error_m", "-0.01"});
}

// LocalizerOptions::laser_localized_sigma_m: a laser's places are held to it, not to
// localized_sigma_m (a sonar ring's). Far below any window's spread, nothing is `localized`
// and the reason names the spread; localized_sigma_m at 0 changes nothing for a laser.
TEST(Tracking, ALasersPlacesAreHeldToTheLaserSpreadLimit) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 9.05; x += 0.1) path.push_back({x, 5.5, 0.0});
  for (const double laser_sigma : {LocalizerOptions{}.laser_localized_sigma_m, 0.001}) {
    LocalizerOptions options = laser_options();
    options.localized_sigma_m = 0.0;
    options.laser_localized_sigma_m = laser_sigma;
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    for (std::size_t k = 0; k < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      localizer.add_observation(double(k), scan_at(map, path[k]));
      const Estimate e = localizer.estimate();
      const HeldBack held_back = localizer.status().held_back;
      EXPECT_TRUE(right(e, path[k])) << laser_sigma << " step " << k;
      if (laser_sigma > 0.01) {
        EXPECT_EQ(e.verdict, Verdict::Localized) << "step " << k << ": " << to_string(held_back);
      } else {
        EXPECT_NE(e.verdict, Verdict::Localized) << "step " << k;
        EXPECT_TRUE(held_back == HeldBack::WideWindow || held_back == HeldBack::WideCarried)
            << "step " << k << ": " << to_string(held_back);
      }
    }
  }
  LocalizerOptions bad = laser_options();
  bad.laser_localized_sigma_m = -1.0;
  test::expect_error([&] { Localizer(map, laser(), bad); }, {"laser_localized_sigma_m"});
}

}  // namespace
}  // namespace gridloc
