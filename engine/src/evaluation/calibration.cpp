// Calibration measures of a reported covariance against the truth (issue 19).
#include "gridloc/engine/evaluation/calibration.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <numbers>

namespace gridloc {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double position_error(const Pose2& estimate, const Pose2& truth) {
  return std::hypot(estimate.x - truth.x, estimate.y - truth.y);
}

/// The squared Mahalanobis distance of the position error over (x, y); infinite without a
/// positive definite xy block.
double position_mahalanobis2(const Pose2& estimate, const Eigen::Matrix3d& covariance,
                             const Pose2& truth) {
  const Eigen::Matrix2d xy = covariance.topLeftCorner<2, 2>();
  if (!xy.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::LLT<Eigen::Matrix2d> factor(xy);
  if (factor.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d error(estimate.x - truth.x, estimate.y - truth.y);
  return error.dot(factor.solve(error));
}

}  // namespace

double pose_nees(const Pose2& estimate, const Eigen::Matrix3d& covariance, const Pose2& truth) {
  if (!covariance.allFinite()) return kNaN;
  const Eigen::LLT<Eigen::Matrix3d> factor(covariance);
  if (factor.info() != Eigen::Success) return kNaN;  // not positive definite
  const Eigen::Vector3d error(estimate.x - truth.x, estimate.y - truth.y,
                              normalize_angle(estimate.theta - truth.theta));
  return error.dot(factor.solve(error));
}

bool within_2sigma_radius(const Pose2& estimate, const Eigen::Matrix3d& covariance,
                          const Pose2& truth) {
  const double variance = 0.5 * (covariance(0, 0) + covariance(1, 1));
  if (!std::isfinite(variance) || variance < 0.0) return false;
  return position_error(estimate, truth) <= 2.0 * std::sqrt(variance);
}

bool within_2sigma_ellipse(const Pose2& estimate, const Eigen::Matrix3d& covariance,
                           const Pose2& truth) {
  return position_mahalanobis2(estimate, covariance, truth) <= 4.0;
}

bool gross_error(double position_error_m, double heading_error_deg) {
  return position_error_m > 0.3 || heading_error_deg > 15.0;
}

CalibrationSummary summarize_calibration(const std::vector<CalibrationSample>& samples) {
  CalibrationSummary summary;
  double nees_sum = 0.0;
  int nees_count = 0, covered = 0;
  for (const CalibrationSample& s : samples) {
    if (!s.localized) continue;
    ++summary.localized;
    const double nees = pose_nees(s.estimate, s.covariance, s.truth);
    if (std::isfinite(nees)) {
      nees_sum += nees;
      ++nees_count;
    }
    covered += within_2sigma_radius(s.estimate, s.covariance, s.truth);
    const double heading_deg =
        std::abs(normalize_angle(s.estimate.theta - s.truth.theta)) * 180.0 / std::numbers::pi;
    summary.gross_localized += gross_error(position_error(s.estimate, s.truth), heading_deg);
  }
  summary.nees_mean = nees_count > 0 ? nees_sum / nees_count : kNaN;
  summary.coverage_2sigma =
      summary.localized > 0 ? static_cast<double>(covered) / summary.localized : kNaN;
  return summary;
}

std::vector<double> coverage_levels() {
  std::vector<double> levels;
  for (int k = 1; k <= 19; ++k) levels.push_back(0.05 * k);
  levels.push_back(0.99);
  return levels;
}

std::vector<double> position_coverage(const std::vector<CalibrationSample>& samples,
                                      const std::vector<double>& probabilities) {
  std::vector<double> distances;  // squared Mahalanobis, of the localized samples
  for (const CalibrationSample& s : samples) {
    if (s.localized) distances.push_back(position_mahalanobis2(s.estimate, s.covariance, s.truth));
  }
  std::vector<double> coverage;
  for (const double p : probabilities) {
    const double quantile = -2.0 * std::log1p(-p);  // chi-squared, 2 degrees of freedom
    std::size_t inside = 0;
    for (const double d : distances) inside += d <= quantile;
    coverage.push_back(distances.empty() ? kNaN : static_cast<double>(inside) / distances.size());
  }
  return coverage;
}

}  // namespace gridloc
