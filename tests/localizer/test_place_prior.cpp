// Tests of engine/src/localizer/place_prior.cpp: the odometry's log prior of a place.
#include "gridloc/engine/localizer/place_prior.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace gridloc {
namespace {

const Eigen::Vector3d kNoFloor = Eigen::Vector3d::Zero();

TEST(PlacePrior, TheCarriedPoseIsTheMostLikely) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.25, 0.25, 0.01).asDiagonal();
  const Pose2 carried{3.0, -1.0, 0.5};
  EXPECT_DOUBLE_EQ(log_prior(carried, carried, covariance, kNoFloor), 0.0);
  EXPECT_LT(log_prior({3.5, -1.0, 0.5}, carried, covariance, kNoFloor), 0.0);
}

TEST(PlacePrior, IsMinusHalfTheSquaredMahalanobisDistance) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.25, 1.0, 0.04).asDiagonal();
  const Pose2 carried{0.0, 0.0, 0.0};
  // 1 m along x is 2 sigma, 1 m along y 1 sigma, 0.4 rad 2 sigma.
  EXPECT_NEAR(log_prior({1.0, 0.0, 0.0}, carried, covariance, kNoFloor), -2.0, 1e-12);
  EXPECT_NEAR(log_prior({0.0, 1.0, 0.0}, carried, covariance, kNoFloor), -0.5, 1e-12);
  EXPECT_NEAR(log_prior({0.0, 0.0, 0.4}, carried, covariance, kNoFloor), -2.0, 1e-12);
}

TEST(PlacePrior, AHeadingTurnedRoundIsFarWhateverItsSign) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(1.0, 1.0, 1.0).asDiagonal();
  const Pose2 carried{0.0, 0.0, 3.0};
  // 3.0 and -3.0 rad are 0.28 rad apart across pi, not 6 rad.
  const double across = log_prior({0.0, 0.0, -3.0}, carried, covariance, kNoFloor);
  const double gap = 2.0 * std::numbers::pi - 6.0;
  EXPECT_NEAR(across, -0.5 * gap * gap, 1e-9);
  EXPECT_LT(log_prior({0.0, 0.0, 3.0 - std::numbers::pi}, carried, covariance, kNoFloor), across);
}

TEST(PlacePrior, TheFloorKeepsASingularCovarianceUsable) {
  const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
  const Eigen::Vector3d floor(0.01, 0.01, 0.0001);
  const double near = log_prior({0.05, 0.0, 0.0}, {}, zero, floor);
  const double far = log_prior({0.5, 0.0, 0.0}, {}, zero, floor);
  EXPECT_NEAR(near, -0.125, 1e-9);
  EXPECT_NEAR(far, -12.5, 1e-9);
}

TEST(PlacePrior, ACorrelatedCovarianceFavoursItsLongAxis) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity() * 0.01;
  covariance(0, 0) = covariance(1, 1) = 1.0;
  covariance(0, 1) = covariance(1, 0) = 0.9;  // unsure along the diagonal x = y
  const double along = log_prior({1.0, 1.0, 0.0}, {}, covariance, kNoFloor);
  const double across = log_prior({1.0, -1.0, 0.0}, {}, covariance, kNoFloor);
  EXPECT_GT(along, across);
}

}  // namespace
}  // namespace gridloc
