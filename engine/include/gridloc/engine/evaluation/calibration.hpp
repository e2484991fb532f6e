#pragma once
/// Whether a reported covariance means what it says (issue 19): the normalized estimation
/// error squared (NEES) of a pose against the truth, the share of position errors within the
/// 2-sigma radius, and the gross errors a verdict let through.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// (estimate - truth)^T covariance^-1 (estimate - truth) over (x, y, theta), the heading
/// difference wrapped into [-pi, pi]: chi-squared with 3 degrees of freedom (mean 3) when the
/// covariance is calibrated. NaN when the covariance is not finite and positive definite.
double pose_nees(const Pose2& estimate, const Eigen::Matrix3d& covariance, const Pose2& truth);

/// Whether the position error lies within the 2-sigma radius, sigma = sqrt((sxx + syy) / 2):
/// about 86 % of a calibrated isotropic 2-D Gaussian's errors do. False for a covariance
/// that is not finite.
bool within_2sigma_radius(const Pose2& estimate, const Eigen::Matrix3d& covariance,
                          const Pose2& truth);

/// Whether the position error lies within the covariance's 2-sigma ellipse (its squared
/// Mahalanobis distance over x, y at most 4: about 86 % of a calibrated 2-D Gaussian's
/// errors do). A corridor's covariance, long along it, covers an error along it that the
/// radius of within_2sigma_radius would not. False for an xy block that is not finite and
/// positive definite.
bool within_2sigma_ellipse(const Pose2& estimate, const Eigen::Matrix3d& covariance,
                           const Pose2& truth);

/// An error a navigation stack must never be handed as `localized`: more than 0.3 m or 15
/// degrees.
bool gross_error(double position_error_m, double heading_error_deg);

/// One answer as the calibration measures read it.
struct CalibrationSample {
  Pose2 estimate;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  Pose2 truth;
  bool localized = false;  ///< the answer's verdict was `localized`
};

struct CalibrationSummary {
  int localized = 0;             ///< answers `localized`: the ones a consumer fuses
  double nees_mean = 0.0;        ///< over those with a usable covariance; NaN without any
  double coverage_2sigma = 0.0;  ///< the share of them within the 2-sigma radius; NaN without any
  int gross_localized = 0;       ///< of them, more than 0.3 m or 15 degrees off
};

/// The calibration of the `localized` answers among `samples`.
CalibrationSummary summarize_calibration(const std::vector<CalibrationSample>& samples);

/// The nominal probabilities a coverage curve is read at: 0.05, 0.10, ..., 0.95 and 0.99.
std::vector<double> coverage_levels();

/// For each nominal probability p of `probabilities` (each in (0, 1)), the share of the
/// `localized` samples whose position error lies within the covariance's p ellipse: its
/// squared Mahalanobis distance over (x, y) at most -2 ln(1 - p), the chi-squared quantile
/// with 2 degrees of freedom. p itself when the covariance is calibrated, above p when it
/// is padded, below when it is optimistic (a calibration plot's curve). A sample without a
/// positive definite xy block counts as outside every ellipse. NaN for every p when no
/// sample is `localized`.
std::vector<double> position_coverage(const std::vector<CalibrationSample>& samples,
                                      const std::vector<double>& probabilities);

}  // namespace gridloc
