// Tests of the Localizer with a laser (issue 13): a corridor that one front scan cannot place
// (two doors look alike) is placed by a short drive; an off-centre laser needs no
// re-projection; bad scans and sensor descriptions are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "gridloc/engine/localizer/localizer.hpp"
#include "laser_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kRange = 3.0;

LocalizerOptions laser_options() {
  LocalizerOptions options;
  options.correlation.resolution = 0.05;  // the map's cell
  return options;
}

LaserSensor front_laser() {
  LaserSensor laser;
  laser.max_range = kRange;
  return laser;
}

double position_error(const Estimate& e, const Pose2& truth) {
  return std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
}

/// Whether `pose` lies within 0.2 m and 5 degrees of `place`.
bool near(const Pose2& pose, const Pose2& place) {
  return std::hypot(pose.x - place.x, pose.y - place.y) < 0.2 &&
         std::abs(normalize_angle(pose.theta - place.theta)) < deg2rad(5.0);
}

/// Whether one of the estimate's alternatives lies near `place`.
bool has_alternative_near(const Estimate& e, const Pose2& place) {
  for (const Hypothesis& h : e.alternatives) {
    if (near(h.pose, place)) return true;
  }
  return false;
}

TEST(LaserLocalizer, OneScanInTheCorridorIsAmbiguous) {
  const OccupancyMap map = test::door_corridor();
  LocalizerOptions options = laser_options();
  options.correlation.hypotheses = 4;  // the look-alikes tie with the truth
  Localizer localizer(map, front_laser(), options);
  const Pose2 truth{10.5, 2.5, 0.0};
  localizer.add_observation(0.0, test::front_scan(map, truth, kRange));
  const Estimate e = localizer.estimate();
  EXPECT_EQ(e.verdict, Verdict::Ambiguous);
  EXPECT_TRUE(has_alternative_near(e, truth));
  // ...as does a look-alike: the other north door, or the south door seen turned.
  ASSERT_GE(e.alternatives.size(), 2u);
  const Pose2 other =
      near(e.alternatives[0].pose, truth) ? e.alternatives[1].pose : e.alternatives[0].pose;
  EXPECT_TRUE(std::hypot(other.x - truth.x, other.y - truth.y) > 1.0 ||
              std::abs(normalize_angle(other.theta - truth.theta)) > deg2rad(90.0));
}

/// A drive past the corridor's south door, checked scan by scan: never `localized` wrongly,
/// `localized` within 5 cm and 1 degree at the end. `tracking_field`: LaserSensor's.
void expect_the_drive_places_it(bool tracking_field) {
  const OccupancyMap map = test::door_corridor();
  // A 3 m front laser: the first scan's look-alikes crowd out the truth (more than the set
  // holds), so the drive's scans are fused into one view that reaches the door.
  LaserSensor laser = front_laser();
  laser.fuse_drive = true;
  laser.tracking_field = tracking_field;
  Localizer localizer(map, laser, laser_options());
  const Pose2 odometry_origin{-3.0, 7.0, 2.0};  // only increments matter
  // The look-alikes' weights part as the drive passes the door; no answer is localized
  // before one place holds nearly all of it (issue 34), and none is localized wrongly. 4 m:
  // the first scan's places are kept down to first_drop_ratio of its best.
  Pose2 truth;
  for (int k = 0; k <= 8; ++k) {
    const Pose2 step{0.5 * k, 0.0, 0.0};
    truth = compose({8.5, 2.5, 0.0}, step);
    localizer.add_odometry(compose(odometry_origin, step));
    localizer.add_observation(k, test::front_scan(map, truth, kRange));
    const Estimate e = localizer.estimate();
    if (e.verdict == Verdict::Localized) {
      EXPECT_LE(position_error(e, truth), 0.05) << k;
    }
  }
  const Estimate e = localizer.estimate();
  EXPECT_EQ(e.verdict, Verdict::Localized);
  EXPECT_LE(position_error(e, truth), 0.05);
  EXPECT_LE(std::abs(normalize_angle(e.pose.theta - truth.theta)), deg2rad(1.0));
}

// By default a laser is tracked on with_laser_tracking_grid's likelihood field (issue 34).
TEST(LaserLocalizer, ADrivePastTheSouthDoorPlacesIt) {
  expect_the_drive_places_it(true);
}

// The options' own grid (the contour-thinned one by default) places it too.
TEST(LaserLocalizer, OnTheOptionsGridTheDrivePlacesItToo) {
  expect_the_drive_places_it(false);
}

// LocalizerOptions::reported_floor_m/_rad: what the caller reads grows by the floor; the
// places, poses and verdicts are those without it.
TEST(LaserLocalizer, TheReportedCovarianceCarriesTheFloorAndNothingElseChanges) {
  const OccupancyMap map = test::door_corridor();
  LocalizerOptions bare = laser_options();
  bare.reported_floor_m = bare.reported_floor_rad = 0.0;
  LaserSensor laser = front_laser();
  laser.fuse_drive = true;
  Localizer with_floor(map, laser, laser_options()), without(map, laser, bare);
  const LocalizerOptions defaults;
  const Eigen::Vector3d floor(defaults.reported_floor_m * defaults.reported_floor_m,
                              defaults.reported_floor_m * defaults.reported_floor_m,
                              defaults.reported_floor_rad * defaults.reported_floor_rad);
  EXPECT_GT(floor.minCoeff(), 0.0);
  for (int k = 0; k <= 8; ++k) {
    const Pose2 truth = compose({8.5, 2.5, 0.0}, {0.5 * k, 0.0, 0.0});
    for (Localizer* localizer : {&with_floor, &without}) {
      localizer->add_odometry(truth);
      localizer->add_observation(k, test::front_scan(map, truth, kRange));
    }
    const Estimate a = with_floor.estimate(), b = without.estimate();
    EXPECT_EQ(a.verdict, b.verdict) << k;
    EXPECT_EQ(a.pose.x, b.pose.x) << k;
    EXPECT_EQ(a.pose.theta, b.pose.theta) << k;
    const Eigen::Matrix3d added = a.covariance - b.covariance;
    EXPECT_TRUE(added.isApprox(Eigen::Matrix3d(floor.asDiagonal()), 1e-9)) << k << "\n" << added;
  }
  bare.reported_floor_m = -0.01;
  test::expect_error([&] { Localizer broken(map, laser, bare); }, {"reported_floor_m"});
}

TEST(LaserLocalizer, TheTrackingGridIsALikelihoodFieldKeepingTheRest) {
  const CorrelationOptions options = with_laser_tracking_grid(laser_options().correlation);
  EXPECT_EQ(options.global, GlobalModel::LikelihoodField);
  EXPECT_EQ(options.field.sigma_m, 0.05);
  EXPECT_EQ(options.field.cutoff_m, 0.15);
  EXPECT_EQ(options.field.free_value, 0.0);
  EXPECT_EQ(options.resolution, 0.05);  // the rest kept
}

TEST(LaserLocalizer, AnOffCentreLaserIsPlacedByItsMount) {
  const OccupancyMap map = test::door_corridor();
  LaserSensor laser = front_laser();
  laser.mount = {0.3, -0.1, -0.2};  // forward, to the right, turned right
  Localizer localizer(map, laser, laser_options());
  const Pose2 robot{10.0, 2.3, -0.4};  // sees the south door and the second north door
  localizer.add_observation(0.0, test::front_scan(map, compose(robot, laser.mount), kRange));
  const Estimate e = localizer.estimate();
  EXPECT_LE(position_error(e, robot), 0.05);
  EXPECT_LE(std::abs(normalize_angle(e.pose.theta - robot.theta)), deg2rad(1.0));
}

TEST(LaserLocalizer, RefusesBadScansAndSensors) {
  const OccupancyMap map = test::door_corridor();
  Localizer localizer(map, front_laser(), laser_options());
  RangeScan scan = test::front_scan(map, {9.6, 2.3, 0.4}, kRange);
  scan.ranges[7] = std::nan("");
  test::expect_error([&] { localizer.add_observation(0.0, scan); }, {"NaN"});
  test::expect_error([&] { localizer.add_observation(0.0, std::vector<double>(14, 1.0)); },
                     {"built for a laser"});
  test::expect_error([&] { localizer.estimate(); }, {"no estimate yet"});
  LaserSensor bad = front_laser();
  bad.max_range = -1.0;
  test::expect_error([&] { Localizer broken(map, bad, laser_options()); }, {"max_range", "-1"});
  bad = front_laser();
  bad.mount.theta = std::numeric_limits<double>::infinity();
  test::expect_error([&] { Localizer broken(map, bad, laser_options()); }, {"mount"});
  bad = front_laser();
  bad.model.model = ScanModel::Rays;
  test::expect_error([&] { Localizer broken(map, bad, laser_options()); }, {"ray model"});
}

}  // namespace
}  // namespace gridloc
