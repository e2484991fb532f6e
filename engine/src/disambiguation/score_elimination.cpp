#include "gridloc/engine/disambiguation/score_elimination.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const ScoreEliminationOptions& options) {
  if (!(options.half_xy > 0.0) || !std::isfinite(options.half_xy)) {
    throw Error("score elimination: half_xy must be > 0 m");
  }
  if (!(options.half_theta >= 0.0) || !std::isfinite(options.half_theta)) {
    throw Error("score elimination: half_theta must be >= 0 rad");
  }
  if (!(options.odometry_error_per_m >= 0.0) || !(options.odometry_turn_error_per_m >= 0.0) ||
      !std::isfinite(options.odometry_error_per_m + options.odometry_turn_error_per_m)) {
    throw Error("score elimination: the odometry errors must be finite and >= 0");
  }
  if (!(options.max_half_xy >= options.half_xy) || !std::isfinite(options.max_half_xy)) {
    throw Error("score elimination: max_half_xy must be >= half_xy");
  }
  if (!(options.drop_ratio > 0.0 && options.drop_ratio <= 1.0)) {
    throw Error("score elimination: drop_ratio must be in (0, 1]");
  }
}

SearchWindow prediction_window(const CorrelationEstimator& estimator,
                               const Observation& observation, const Pose2& predicted,
                               double travelled_m, const ScoreEliminationOptions& options) {
  const SearchWindow global = estimator.global_window(observation);
  const double turn = options.odometry_turn_error_per_m * travelled_m;
  const double drift = options.odometry_error_per_m * travelled_m + 0.5 * turn * travelled_m;
  return {predicted, std::min(options.max_half_xy, options.half_xy + 3.0 * drift),
          std::min(std::numbers::pi, options.half_theta + 3.0 * turn), global.step_xy,
          global.step_theta};
}

std::vector<Estimate> score_predictions(const CorrelationEstimator& estimator,
                                        const Observation& observation,
                                        const std::vector<Pose2>& predicted, double travelled_m,
                                        const ScoreEliminationOptions& options) {
  validate(options);
  if (!(travelled_m >= 0.0) || !std::isfinite(travelled_m)) {
    throw Error("score elimination: the distance travelled must be >= 0 m");
  }
  std::vector<Estimate> estimates;
  estimates.reserve(predicted.size());
  for (const Pose2& pose : predicted) {
    estimates.push_back(estimator.estimate(
        observation, prediction_window(estimator, observation, pose, travelled_m, options)));
  }
  return estimates;
}

std::vector<int> within_drop_ratio(const std::vector<double>& scores, double drop_ratio) {
  if (!(drop_ratio > 0.0 && drop_ratio <= 1.0)) {
    throw Error("score elimination: drop_ratio must be in (0, 1]");
  }
  std::vector<int> kept;
  if (scores.empty()) return kept;
  const double best = *std::max_element(scores.begin(), scores.end());
  const double floor = best > 0.0 ? drop_ratio * best : best;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    if (scores[i] >= floor) kept.push_back(static_cast<int>(i));
  }
  return kept;
}

}  // namespace gridloc
