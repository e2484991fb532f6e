// Tests of engine/evaluation/calibration.hpp (issue 19): NEES against brute force, the 2-sigma
// radius, gross errors, and the summary over the `localized` answers.
#include "gridloc/engine/evaluation/calibration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

namespace gridloc {
namespace {

TEST(Calibration, NeesIsTheMahalanobisDistanceSquaredWithTheHeadingWrapped) {
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  EXPECT_DOUBLE_EQ(pose_nees({1.0, 2.0, 0.0}, identity, {0.0, 0.0, 0.0}), 5.0);
  // 179 deg and -179 deg are 2 degrees apart, not 358.
  const double two_deg = 2.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(pose_nees({0.0, 0.0, std::numbers::pi - 0.5 * two_deg}, identity,
                        {0.0, 0.0, -std::numbers::pi + 0.5 * two_deg}),
              two_deg * two_deg, 1e-12);
  // Against the inverse computed by hand for random positive definite covariances.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 50; ++k) {
    Eigen::Matrix3d a;
    for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = normal(rng);
    const Eigen::Matrix3d covariance = a * a.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    const Pose2 estimate{normal(rng), normal(rng), 0.3 * normal(rng)};
    const Pose2 truth{normal(rng), normal(rng), 0.3 * normal(rng)};
    const Eigen::Vector3d e(estimate.x - truth.x, estimate.y - truth.y,
                            normalize_angle(estimate.theta - truth.theta));
    const double expected = e.transpose() * covariance.inverse() * e;
    EXPECT_NEAR(pose_nees(estimate, covariance, truth), expected, 1e-9 * (1.0 + expected));
  }
}

TEST(Calibration, NeesIsNaNWithoutAUsableCovariance) {
  EXPECT_TRUE(std::isnan(pose_nees({1, 0, 0}, Eigen::Matrix3d::Zero(), {0, 0, 0})));
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(0, 0) = std::nan("");
  EXPECT_TRUE(std::isnan(pose_nees({1, 0, 0}, bad, {0, 0, 0})));
}

TEST(Calibration, TheTwoSigmaRadiusUsesTheMeanPositionVariance) {
  // sxx = 0.01, syy = 0.03: sigma = sqrt(0.02), the radius 2 sigma = 0.2828 m.
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.01, 0.03, 0.01).asDiagonal();
  EXPECT_TRUE(within_2sigma_radius({0.28, 0.0, 0.0}, covariance, {0, 0, 0}));
  EXPECT_FALSE(within_2sigma_radius({0.0, 0.29, 0.0}, covariance, {0, 0, 0}));
  Eigen::Matrix3d bad = covariance;
  bad(1, 1) = INFINITY;
  EXPECT_FALSE(within_2sigma_radius({0.0, 0.0, 0.0}, bad, {0, 0, 0}));
}

TEST(Calibration, TheTwoSigmaEllipseFollowsACorridor) {
  // A corridor along x: sigma 0.2 m along it, 0.02 m across, turned by 30 degrees.
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  Eigen::Matrix2d rotate;
  rotate << c, -s, s, c;
  covariance.topLeftCorner<2, 2>() =
      rotate * Eigen::Vector2d(0.04, 0.0004).asDiagonal() * rotate.transpose();
  covariance(2, 2) = 1e-4;
  // 0.39 m along the corridor is within 2 sigma; 0.05 m across it is not.
  EXPECT_TRUE(within_2sigma_ellipse({0.39 * c, 0.39 * s, 0.0}, covariance, {0, 0, 0}));
  EXPECT_FALSE(within_2sigma_ellipse({0.41 * c, 0.41 * s, 0.0}, covariance, {0, 0, 0}));
  EXPECT_FALSE(within_2sigma_ellipse({-0.05 * s, 0.05 * c, 0.0}, covariance, {0, 0, 0}));
  EXPECT_TRUE(within_2sigma_ellipse({-0.03 * s, 0.03 * c, 0.0}, covariance, {0, 0, 0}));
  // The radius test of the mean variance (sigma 0.14 m) says otherwise along and across.
  EXPECT_FALSE(within_2sigma_radius({0.39 * c, 0.39 * s, 0.0}, covariance, {0, 0, 0}));
  EXPECT_TRUE(within_2sigma_radius({-0.05 * s, 0.05 * c, 0.0}, covariance, {0, 0, 0}));
  EXPECT_FALSE(within_2sigma_ellipse({0, 0, 0}, Eigen::Matrix3d::Zero(), {0, 0, 0}));
}

TEST(Calibration, GrossIsBeyondThirtyCentimetresOrFifteenDegrees) {
  EXPECT_FALSE(gross_error(0.3, 15.0));
  EXPECT_TRUE(gross_error(0.31, 0.0));
  EXPECT_TRUE(gross_error(0.0, 15.1));
}

TEST(Calibration, TheSummaryReadsTheLocalizedAnswersOnly) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal();
  std::vector<CalibrationSample> samples = {
      {{0.1, 0.0, 0.0}, covariance, {0, 0, 0}, true},   // NEES 1, within 2 sigma (0.2 m)
      {{0.3, 0.0, 0.0}, covariance, {0, 0, 0}, true},   // NEES 9, outside
      {{1.0, 0.0, 0.0}, covariance, {0, 0, 0}, true},   // NEES 100, outside, gross
      {{5.0, 0.0, 0.0}, covariance, {0, 0, 0}, false},  // not localized: not read
  };
  const CalibrationSummary s = summarize_calibration(samples);
  EXPECT_EQ(s.localized, 3);
  EXPECT_NEAR(s.nees_mean, (1.0 + 9.0 + 100.0) / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.coverage_2sigma, 1.0 / 3.0);
  EXPECT_EQ(s.gross_localized, 1);
  samples.resize(1);
  samples[0].localized = false;
  const CalibrationSummary none = summarize_calibration(samples);
  EXPECT_EQ(none.localized, 0);
  EXPECT_TRUE(std::isnan(none.nees_mean));
  EXPECT_TRUE(std::isnan(none.coverage_2sigma));
}

// Errors drawn from the reported covariance itself fill each p ellipse a share p of the
// time; a covariance four times too large (padded) covers more, one four times too small
// (optimistic) less.
TEST(Calibration, ACoverageCurveFollowsTheDiagonalWhenCalibrated) {
  Eigen::Matrix3d covariance;
  covariance << 0.04, 0.012, 0.0, 0.012, 0.01, 0.0, 0.0, 0.0, 0.001;  // a corridor along x
  const Eigen::Matrix2d root = covariance.topLeftCorner<2, 2>().llt().matrixL();
  std::mt19937_64 rng(19);
  std::normal_distribution<double> normal;
  std::vector<CalibrationSample> calibrated, padded, optimistic;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector2d e = root * Eigen::Vector2d(normal(rng), normal(rng));
    const Pose2 estimate{e.x(), e.y(), 0.0};
    calibrated.push_back({estimate, covariance, {0, 0, 0}, true});
    padded.push_back({estimate, 4.0 * covariance, {0, 0, 0}, true});
    optimistic.push_back({estimate, 0.25 * covariance, {0, 0, 0}, true});
  }
  calibrated.push_back({{9.0, 0.0, 0.0}, covariance, {0, 0, 0}, false});  // not read
  const std::vector<double> levels = coverage_levels();
  ASSERT_EQ(levels.size(), 20u);
  EXPECT_DOUBLE_EQ(levels.front(), 0.05);
  EXPECT_DOUBLE_EQ(levels.back(), 0.99);
  const std::vector<double> fair = position_coverage(calibrated, levels);
  const std::vector<double> wide = position_coverage(padded, levels);
  const std::vector<double> narrow = position_coverage(optimistic, levels);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    EXPECT_NEAR(fair[k], levels[k], 0.015) << levels[k];
    if (levels[k] < 0.99) {
      EXPECT_GT(wide[k], levels[k] + 0.04) << levels[k];  // 1 - (1 - p)^4
    }
    EXPECT_LT(narrow[k], 0.75 * levels[k]) << levels[k];  // 1 - (1 - p)^(1/4)
  }
  // The 2-sigma ellipse holds 1 - exp(-2) = 86.5 % of a calibrated 2-D Gaussian's errors.
  EXPECT_NEAR(position_coverage(calibrated, {1.0 - std::exp(-2.0)})[0], 0.865, 0.015);
  // No covariance: outside every ellipse; nothing localized: NaN.
  std::vector<CalibrationSample> none = {
      {{0.0, 0.0, 0.0}, Eigen::Matrix3d::Zero(), {0, 0, 0}, true}};
  EXPECT_DOUBLE_EQ(position_coverage(none, {0.5})[0], 0.0);
  none[0].localized = false;
  EXPECT_TRUE(std::isnan(position_coverage(none, {0.5})[0]));
}

}  // namespace
}  // namespace gridloc
