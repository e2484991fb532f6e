// Tests of engine/src/localizer/localizer.cpp: the navigation stack's facade (issue 13):
// global from a standstill, tracking through odometry, a drive that places the corridor,
// driver values and bad input.
#include "gridloc/engine/localizer/localizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const SonarRing& ring() {
  static const SonarRing loaded = load_sonar_ring(test::ring_path());
  return loaded;
}

double position_error(const Estimate& e, const Pose2& truth) {
  return std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
}

double heading_error(const Estimate& e, const Pose2& truth) {
  return std::abs(normalize_angle(e.pose.theta - truth.theta));
}

/// The driver's view of a noise-free firing: no echo is +inf.
std::vector<double> driver_firing(const OccupancyMap& map, const Pose2& pose) {
  std::vector<double> ranges = simulate_sonar(map, ring(), pose, SonarSimOptions{});
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (ranges[i] >= ring().sonars[i].max_range)
      ranges[i] = std::numeric_limits<double>::infinity();
  }
  return ranges;
}

// From no prior a standstill firing finds the place, but it is `not localized` (confirming)
// until the drive bears it out (JumpGateOptions::settle_first); without the rule, at once.
TEST(Localizer, AStandstillFiringLocalizesGlobally) {
  const OccupancyMap map = load_ros_map(test::map_path("room_furnished"));
  for (const bool settle_first : {true, false}) {
    LocalizerOptions options;
    options.jump_gate.settle_first = settle_first;
    Localizer localizer(map, ring(), options);
    test::expect_error([&] { localizer.estimate(); }, {"no estimate yet"});
    const Pose2 truth{2.42, 2.27, -0.35};
    localizer.add_observation(0.0, driver_firing(map, truth));
    const Estimate e = localizer.estimate();
    EXPECT_LE(position_error(e, truth), 0.10);
    EXPECT_LE(heading_error(e, truth), deg2rad(7.0));
    EXPECT_EQ(e.verdict, settle_first ? Verdict::NotLocalized : Verdict::Localized);
    EXPECT_EQ(localizer.status().confirming, settle_first);
    EXPECT_FALSE(localizer.status().jump_rejected);
  }
}

TEST(Localizer, TracksThroughOdometryInItsOwnFrame) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  Localizer localizer(map, ring());
  // The odometry frame is the world turned and shifted: only its increments matter.
  const Pose2 odometry_origin{10.0, -4.0, 1.0};
  const Pose2 start{1.5, 1.5, 0.3};
  localizer.add_odometry(odometry_origin);
  localizer.set_prior({1.7, 1.3, 0.5}, Eigen::Vector3d(0.04, 0.04, 0.03).asDiagonal());
  for (int k = 0; k <= 6; ++k) {
    const Pose2 step{0.25 * k, 0.0, 0.05 * k};
    const Pose2 truth = compose(start, step);
    localizer.add_odometry(compose(odometry_origin, step));
    localizer.add_observation(0.5 * k, driver_firing(map, truth));
    const Estimate e = localizer.estimate();
    EXPECT_LE(position_error(e, truth), 0.10) << "firing " << k;
    EXPECT_LE(heading_error(e, truth), deg2rad(7.0)) << "firing " << k;
  }
}

TEST(Localizer, ResetForgetsTheDriveAndThePrior) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  Localizer localizer(map, ring());
  const Pose2 truth{2.0, 1.5, 0.5};
  localizer.set_prior({4.5, 3.5, -2.0}, Eigen::Matrix3d::Identity() * 0.01);  // wrong
  localizer.add_observation(0.0, driver_firing(map, truth));
  EXPECT_GT(position_error(localizer.estimate(), truth), 0.5);  // the window missed the truth
  localizer.reset();
  test::expect_error([&] { localizer.estimate(); }, {"no estimate yet"});
  localizer.add_observation(1.0, driver_firing(map, truth));  // global again
  EXPECT_LE(position_error(localizer.estimate(), truth), 0.10);
}

TEST(Localizer, ResetKeepsTheOdometryPose) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  Localizer localizer(map, ring());
  const Pose2 truth{2.0, 1.5, 0.5};
  localizer.add_odometry({1.0, 0.0, 0.0});
  localizer.reset();
  localizer.set_prior(truth, Eigen::Matrix3d::Identity() * 1e-4);  // at odometry (1, 0, 0)
  localizer.add_odometry({1.0, 0.0, 0.0});                         // not moved
  localizer.add_observation(0.0, driver_firing(map, truth));
  EXPECT_LE(position_error(localizer.estimate(), truth), 0.10);
}

TEST(Localizer, AWrongPriorGivesWayOnceTheDriveConfirmsTheReSearchsPlace) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  LocalizerOptions options;
  options.misses_before_global = 2;
  Localizer localizer(map, ring(), options);
  const Pose2 start{2.0, 1.5, 0.5};
  localizer.set_prior({4.5, 3.5, -2.0}, Eigen::Matrix3d::Identity() * 0.01);  // wrong
  for (int k = 0; k < 2; ++k) {
    localizer.add_observation(k, driver_firing(map, start));
    EXPECT_EQ(localizer.estimate().verdict, Verdict::NotLocalized);
  }
  // Two misses: the second firing searched the whole map (one slice in a room this small),
  // and the truth joined the prior as a hypothesis.
  EXPECT_TRUE(localizer.status().search_finished);
  bool truth_tracked = false;
  for (const Hypothesis& h : localizer.estimate().alternatives) {
    truth_tracked = truth_tracked || std::hypot(h.pose.x - start.x, h.pose.y - start.y) < 0.1;
  }
  EXPECT_TRUE(truth_tracked);
  // A short drive weighs them: the prior explains nothing, the truth everything; the truth
  // contradicts the prior the user gave, so the jump gate holds it for a metre.
  Verdict last = Verdict::NotLocalized;
  Pose2 truth = start;
  for (int k = 1; k <= 15 && last != Verdict::Localized; ++k) {
    truth = compose(start, {0.1 * k, 0.0, 0.0});
    localizer.add_odometry({0.1 * k, 0.0, 0.0});
    localizer.add_observation(2 + k, driver_firing(map, truth));
    last = localizer.estimate().verdict;
  }
  EXPECT_EQ(last, Verdict::Localized);
  EXPECT_LE(position_error(localizer.estimate(), truth), 0.10);
}

TEST(Localizer, BadInputIsRefusedAndLeavesTheStateAsItWas) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  Localizer localizer(map, ring());
  std::vector<double> firing = driver_firing(map, {2.0, 1.5, 0.5});
  localizer.add_observation(0.0, firing);
  const Estimate before = localizer.estimate();
  firing[4] = std::nan("");
  test::expect_error([&] { localizer.add_observation(1.0, firing); }, {"sonar 4", "NaN"});
  test::expect_error([&] { localizer.add_odometry({0.0, std::nan(""), 0.0}); }, {"odometry"});
  test::expect_error(
      [&] {
        localizer.set_prior({0, 0, 0}, -Eigen::Matrix3d::Identity());
      },
      {"covariance"});
  test::expect_error([&] { localizer.add_observation(std::nan(""), firing); }, {"time"});
  RangeScan scan;
  scan.angles = {0.0};
  scan.ranges = {1.0};
  test::expect_error([&] { localizer.add_observation(2.0, scan); }, {"built for a sonar ring"});
  const Estimate after = localizer.estimate();
  EXPECT_EQ(after.pose.x, before.pose.x);
  EXPECT_EQ(after.pose.y, before.pose.y);
  EXPECT_EQ(after.score, before.score);
  LocalizerOptions options;
  options.drive.max_firings = 0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"max_firings"});
  options = {};
  options.max_half_xy_m = 0.1;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"max_half_xy_m", "0.1"});
  options = {};
  options.prior_sigmas = -1.0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"prior_sigmas", "-1"});
  options = {};
  options.misses_before_global = 0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"misses_before_global"});
  options = {};
  options.far_place_margin = -0.5;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"far_place_margin"});
  options = {};
  options.weights.entry_weight = 2.0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"entry_weight"});
  options = {};
  options.jump_gate.settle_updates = 0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"settle_updates"});
  options = {};
  options.research.slices_per_update = 0;
  test::expect_error([&] { Localizer bad(map, ring(), options); }, {"slices_per_update"});
}

}  // namespace
}  // namespace gridloc
