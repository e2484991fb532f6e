// Tests of engine/src/icp/robust_icp.cpp: Huber weight, segmentation and C_f (seed 004 §3.2),
// exact recovery on a noise-free hallway pair and robustness to 30 % outliers (seed 004 §4's
// simulation: motion 500 mm, -200 mm, 20 deg), and input validation.
#include "gridloc/engine/icp/robust_icp.hpp"

#include "gridloc/engine/evaluation/hallway_trials.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include "gridloc/sensors/scan_disturbances.hpp"
#include "gridloc/sensors/segment_world.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using Points = std::vector<Eigen::Vector2d>;

/// A noise-free 360 deg scan at `pose` of seed004_hallway() (0.5 deg steps like seed 004's
/// sensor, 8 m max range), the returns as points in the robot frame, ordered by bearing.
Points scan_at(const Pose2& pose) {
  static const std::vector<WallSegment> walls = seed004_hallway();
  const RangeScan scan =
      simulate_segment_scan(walls, pose, 720, deg2rad(-180.0), deg2rad(0.5), 8.0);
  Points out;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (r < scan.max_range)
      out.emplace_back(r * std::cos(scan.angles[k]), r * std::sin(scan.angles[k]));
  }
  return out;
}

Points with_outliers(const Points& pts, double share, unsigned seed) {
  return scatter_outliers(pts, share, 3.0, seed);
}

const Pose2 kMotion{0.5, -0.2, deg2rad(20.0)};  // seed 004 §4

double pos_err(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
double ang_err(const Pose2& a, const Pose2& b) {
  return std::abs(normalize_angle(a.theta - b.theta));
}

IcpResult timed_match(const Points& ref, const Points& cur, const IcpOptions& o,
                      const char* label) {
  const auto t0 = std::chrono::steady_clock::now();
  const IcpResult r = match_scans(ref, cur, Pose2{}, o);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "[" << label << "] error " << 1000 * std::abs(r.pose.x - kMotion.x) << " mm, "
            << 1000 * std::abs(r.pose.y - kMotion.y) << " mm, " << rad2deg(ang_err(r.pose, kMotion))
            << " deg; " << r.iterations << " iterations, converged " << r.converged << ", rms "
            << 1000 * r.rms_m << " mm, inliers " << r.inlier_share << ", pairs " << r.pairs << ", "
            << ms << " ms\n";
  return r;
}

TEST(HuberWeight, OneInsideAndKOverRBeyond) {
  EXPECT_DOUBLE_EQ(huber_weight(0.0, 1.345), 1.0);
  EXPECT_DOUBLE_EQ(huber_weight(0.5, 1.345), 1.0);
  EXPECT_DOUBLE_EQ(huber_weight(-1.345, 1.345), 1.0);
  EXPECT_DOUBLE_EQ(huber_weight(2.69, 1.345), 0.5);
  EXPECT_DOUBLE_EQ(huber_weight(-4.035, 1.345), 1.0 / 3.0);
}

TEST(HuberWeight, ScaleIsMadOrStdDevWithAFloor) {
  const std::vector<double> r{1.0, -2.0, 3.0, -4.0, 100.0};
  EXPECT_DOUBLE_EQ(residual_scale(r, HuberScale::kMad, 1e-6), 1.4826 * 3.0);
  const std::vector<double> s{-1.0, 1.0};
  EXPECT_DOUBLE_EQ(residual_scale(s, HuberScale::kStdDev, 1e-6), 1.0);
  EXPECT_DOUBLE_EQ(residual_scale({0.0, 0.0, 0.0}, HuberScale::kMad, 1e-6), 1e-6);
}

TEST(SegmentScan, SplitsOnAGap) {
  Points pts;
  for (int i = 0; i < 10; ++i) pts.emplace_back(0.02 * i, 1.0);
  for (int i = 0; i < 5; ++i) pts.emplace_back(0.7 + 0.02 * i, 1.0);
  const auto segs = segment_scan(pts, 0.08);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].begin, 0u);
  EXPECT_EQ(segs[0].end, 10u);
  EXPECT_EQ(segs[1].begin, 10u);
  EXPECT_EQ(segs[1].end, 15u);
  EXPECT_NEAR(std::abs(segs[0].direction.x()), 1.0, 1e-12);
}

TEST(SegmentComplexity, StraightIsTenthAndExactForATriangle) {
  Points line;
  for (int i = 0; i < 20; ++i) line.emplace_back(0.03 * i, 0.5 + 0.015 * i);
  const auto s = segment_scan(line, 0.08);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].mean_distance_m, 0.0, 1e-12);
  EXPECT_NEAR(s[0].complexity, 0.1, 1e-12);
  EXPECT_EQ(s[0].matching_points, 2u);  // ceil(0.1 * 20)

  // (0,0), (2,0), (1,1): TLS line y = 1/3, distances 1/3, 1/3, 2/3 -> d_m = 4/9.
  const Points tri{{0, 0}, {2, 0}, {1, 1}};
  const auto t = segment_scan(tri, 10.0, 0.1);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].mean_distance_m, 4.0 / 9.0, 1e-12);
  EXPECT_NEAR(t[0].complexity, (4.0 / 9.0 + 0.1) / 1.0, 1e-12);
  EXPECT_EQ(t[0].matching_points, 2u);                 // ceil(0.544 * 3)
  EXPECT_DOUBLE_EQ(shape_complexity(1.0, 0.04), 1.0);  // clipped at 1
}

TEST(SegmentComplexity, CornerAndArcAreMoreComplexThanAWall) {
  Points wall, corner, arc;
  for (int i = 0; i < 30; ++i) wall.emplace_back(1.0, -0.6 + 0.04 * i);
  for (int i = 0; i < 15; ++i) corner.emplace_back(1.0, -0.6 + 0.04 * i);
  for (int i = 1; i <= 15; ++i) corner.emplace_back(1.0 - 0.04 * i, -0.04);
  for (int i = 0; i < 30; ++i) {
    const double a = deg2rad(3.0 * i);
    arc.emplace_back(0.8 * std::cos(a), 0.8 * std::sin(a));
  }
  const double cw = segment_scan(wall, 0.08)[0].complexity;
  const double cc = segment_scan(corner, 0.08)[0].complexity;
  const double ca = segment_scan(arc, 0.08)[0].complexity;
  EXPECT_LT(cw, cc);
  EXPECT_LT(cw, ca);
  EXPECT_GT(segment_scan(arc, 0.08)[0].matching_points,
            segment_scan(wall, 0.08)[0].matching_points);
}

TEST(RobustIcp, ExactRecoveryOnNoiseFreeHallway) {
  const Points ref = scan_at({0, 0, 0});
  const Points cur = scan_at(kMotion);
  const IcpResult r = timed_match(ref, cur, IcpOptions{}, "no outliers, C_f points");
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.pose.x, kMotion.x, 1e-6);
  EXPECT_NEAR(r.pose.y, kMotion.y, 1e-6);
  EXPECT_NEAR(ang_err(r.pose, kMotion), 0.0, 1e-6);

  IcpOptions all;
  all.use_complexity = false;
  const IcpResult a = timed_match(ref, cur, all, "no outliers, all points");
  EXPECT_TRUE(a.converged);
  EXPECT_NEAR(pos_err(a.pose, kMotion), 0.0, 1e-6);
  EXPECT_NEAR(ang_err(a.pose, kMotion), 0.0, 1e-6);
}

// Measured (Release, x86-64, GCC): every robust run below lands within 0.0003 mm and 2e-5 deg
// of the truth, while plain least squares is off by 4-17 cm and 0.8-4.7 deg; the bounds leave
// a wide margin.
constexpr double kRobustXy = 1e-3;
constexpr double kRobustThetaDeg = 0.05;

TEST(RobustIcp, SegmentationDropsScatteredOutliers) {
  // 30 % of the current scan replaced by random points: nearly all become segments of one or
  // two points, which the default min_segment_points = 3 drops (seed 004 §3.2's noise reduction).
  const Points ref = scan_at({0, 0, 0});
  for (unsigned seed : {4u, 5u, 6u}) {
    const Points cur = with_outliers(scan_at(kMotion), 0.30, seed);
    const IcpResult r = timed_match(ref, cur, IcpOptions{}, "30% scattered outliers, defaults");
    EXPECT_LT(pos_err(r.pose, kMotion), kRobustXy) << "seed " << seed;
    EXPECT_LT(rad2deg(ang_err(r.pose, kMotion)), kRobustThetaDeg) << "seed " << seed;
  }
}

TEST(RobustIcp, HuberRejectsScatteredOutliersThatLeastSquaresFollows) {
  // Same outliers with segmentation's filter and C_f sampling off, so only the M-estimator
  // stands between them and the estimate.
  const Points ref = scan_at({0, 0, 0});
  IcpOptions huber;
  // A 2 m reach: the default 0.5 m already keeps most outliers out, for both estimators.
  huber.max_correspondence_m = 2.0;
  huber.min_segment_points = 1;
  huber.use_complexity = false;
  IcpOptions plain = huber;
  plain.robust = false;
  for (unsigned seed : {4u, 5u, 6u}) {
    const Points cur = with_outliers(scan_at(kMotion), 0.30, seed);
    const IcpResult r = timed_match(ref, cur, huber, "30% scattered outliers, Huber, all points");
    EXPECT_LT(pos_err(r.pose, kMotion), kRobustXy) << "seed " << seed;
    EXPECT_LT(rad2deg(ang_err(r.pose, kMotion)), kRobustThetaDeg) << "seed " << seed;
    const IcpResult p = timed_match(ref, cur, plain, "30% scattered outliers, least squares");
    // Least squares follows the outliers: millimetres to centimetres off, 1000x Huber's error.
    EXPECT_GT(pos_err(p.pose, kMotion), 1000.0 * pos_err(r.pose, kMotion)) << "seed " << seed;
  }
}

/// Successes of seed 004's hallway trials over seeds 1..n (run_hallway_trials).
int successes(int n, const IcpOptions& icp, double noise_m, double xy, double theta_deg,
              OutlierKind outliers) {
  HallwayTrialsOptions o;
  o.seeds = n;
  o.icp = icp;
  o.noise_m = noise_m;
  o.outliers = outliers;
  o.success_xy = xy;
  o.success_deg = theta_deg;
  const HallwayReport r = run_hallway_trials(o);
  EXPECT_EQ(r.seeds, n);
  return r.successes;
}

TEST(RobustIcp, HuberRejectsAppearingObstacles) {
  // Seed 004 §4: "most of the outliers are occlusion or appearance of obstacles". 30 % of the
  // current scan, in four runs, is pulled 20-60 % closer, as if obstacles had appeared; these
  // runs form long segments that segmentation keeps, so only Huber can reject them. Measured
  // over seeds 1-100 (`gridloc hallway --outliers appearing`, engine/doc/icp.md): Huber 93
  // within 1 mm (the others stop in another basin: the phantoms hide what pins the 20 deg
  // turn), least squares none.
  IcpOptions plain;
  plain.robust = false;
  const int huber = successes(20, IcpOptions{}, 0.0, 1e-3, 0.01, OutlierKind::Appearing);
  const int least_squares = successes(20, plain, 0.0, 1e-3, 0.01, OutlierKind::Appearing);
  std::cout << "[appearing obstacles] within 1 mm: Huber " << huber << "/20, least squares "
            << least_squares << "/20\n";
  EXPECT_GE(huber, 16);
  EXPECT_EQ(least_squares, 0);
}

TEST(RobustIcp, NoisyHallwayStaysWithinTheSeedsFigures) {
  // Seed 004 §4 with sensor noise: 2 cm Gaussian range noise on both scans (half of its
  // sensor's 40.1 mm pixel), with and without 30 % scattered outliers. Seed 004 reports
  // 11.66 mm, 5.06 mm and 0.06 deg. Measured over seeds 1-100 (`gridloc hallway --noise
  // 0.02`): every run within 3 cm and 0.3 deg, mean errors 4.6 / 3.2 mm and 0.03 deg (clean),
  // 5.5 / 1.9 mm and 0.05 deg (outliers). With chord tangents (tangent_points = 2) half of the
  // outlier runs drifted along the hallway.
  EXPECT_EQ(successes(10, IcpOptions{}, 0.02, 0.03, 0.3, OutlierKind::None), 10);
  EXPECT_EQ(successes(10, IcpOptions{}, 0.02, 0.03, 0.3, OutlierKind::Scattered), 10);
  IcpOptions chords;
  chords.tangent_points = 2;
  EXPECT_LT(successes(10, chords, 0.02, 0.03, 0.3, OutlierKind::Scattered), 10);
  test::expect_error([] { parse_outlier_kind("rain"); }, {"none, scattered or appearing"});
}

TEST(SegmentScan, AdaptiveGapNeverJoinsACoarseScanWhole) {
  // The adaptive part r sin d / sin(lambda - d) explodes as the beam step d nears lambda; it
  // applies only up to lambda / 2 and to at most 4 beam spacings. The hallway keeps at least
  // 4 separate pieces (the column, the pillar's edges, the recess) whatever the beam count;
  // without the cap 90 beams gave 2 segments.
  for (int beams : {36, 37, 40, 45, 60, 90, 180, 360, 720}) {
    const RangeScan s = simulate_segment_scan(seed004_hallway(), {0, 0, 0}, beams, deg2rad(-180.0),
                                              2 * M_PI / beams, 8.0);
    const auto segs = segment_scan(scan_returns(s), 0.08, 0.04, deg2rad(10.0));
    EXPECT_GE(segs.size(), 4u) << beams << " beams";
  }
}

TEST(RobustIcp, CovarianceMatchesTheScatterOfNoisyMatches) {
  // 60 noisy matches of the hallway pair: the reported standard deviations (of x, y, theta
  // of the pose, turned 20 deg and 0.5 m from the reference) agree with the scatter of the
  // estimates within a factor of 3. Measured: reported / sample 0.61, 0.51, 1.21: the
  // Gauss-Newton covariance ignores the tangents' own noise and is optimistic in position by
  // about 2x (engine/doc/icp.md).
  std::vector<Pose2> poses;
  Eigen::Vector3d reported = Eigen::Vector3d::Zero();
  const int n = 60;
  for (int k = 0; k < n; ++k) {
    RangeScan a = simulate_segment_scan(seed004_hallway(), {0, 0, 0}, 720, deg2rad(-180.0),
                                        deg2rad(0.5), 8.0);
    RangeScan b =
        simulate_segment_scan(seed004_hallway(), kMotion, 720, deg2rad(-180.0), deg2rad(0.5), 8.0);
    add_range_noise(a, 0.01, 5000 + 2 * k);
    add_range_noise(b, 0.01, 5001 + 2 * k);
    const IcpResult r = match_scans(scan_returns(a), scan_returns(b), kMotion, IcpOptions{});
    poses.push_back(r.pose);
    reported += r.covariance.diagonal().cwiseSqrt() / n;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), var = Eigen::Vector3d::Zero();
  for (const Pose2& p : poses) mean += Eigen::Vector3d(p.x, p.y, p.theta) / n;
  for (const Pose2& p : poses) {
    const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.theta) - mean;
    var += d.cwiseProduct(d) / (n - 1);
  }
  const Eigen::Vector3d sample = var.cwiseSqrt();
  std::cout << "[covariance] reported std " << reported.transpose() << ", sample std "
            << sample.transpose() << "\n";
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(reported[i], sample[i] / 3.0) << i;
    EXPECT_LT(reported[i], 3.0 * sample[i]) << i;
  }
}

TEST(RobustIcp, NoPairsWithinReachIsNotConverged) {
  IcpOptions o;
  o.max_correspondence_m = 1e-9;  // also checks the bucket grid stays small for a tiny radius
  const IcpResult r = match_scans(scan_at({0, 0, 0}), scan_at(kMotion), Pose2{}, o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.pairs, 0u);
}

TEST(RobustIcp, BadInputIsNamed) {
  const Points ok{{1, 0}, {1, 0.05}, {1, 0.1}, {1, 0.15}};
  test::expect_error([&] { match_scans({}, ok); }, {"reference scan has 0 points"});
  test::expect_error([&] { match_scans(ok, {{1, 0}}); }, {"current scan has 1 points"});
  Points nan = ok;
  nan[2].y() = std::numeric_limits<double>::quiet_NaN();
  test::expect_error([&] { match_scans(ok, nan); }, {"current point 2", "not finite"});
  test::expect_error([&] { match_scans(nan, ok); }, {"reference point 2", "not finite"});
  IcpOptions o;
  o.gap_m = 0.0;
  test::expect_error([&] { match_scans(ok, ok, {}, o); }, {"gap_m"});
  o = {};
  o.max_iterations = 0;
  test::expect_error([&] { match_scans(ok, ok, {}, o); }, {"max_iterations", "0"});
  o = {};
  o.huber_k = -1.0;
  test::expect_error([&] { match_scans(ok, ok, {}, o); }, {"huber_k"});
  test::expect_error([&] { match_scans(ok, ok, {0, std::nan(""), 0}); }, {"initial pose"});
  test::expect_error([&] { segment_scan(ok, -1.0); }, {"gap_m"});
  const Points sparse{{0, 0}, {1, 0}, {2, 0}};
  test::expect_error([&] { match_scans(sparse, ok); }, {"no segment of 2 or more points"});
}

}  // namespace
}  // namespace gridloc
