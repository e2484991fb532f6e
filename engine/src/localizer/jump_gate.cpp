// The jump gate: a localized answer must agree with the last one carried by odometry.
#include "gridloc/engine/localizer/jump_gate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const JumpGateOptions& options) {
  const auto ok = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!ok(options.sigmas) || !ok(options.min_m) || !ok(options.min_rad) ||
      !ok(options.odometry_error_per_m) || !ok(options.odometry_turn_error_per_m) ||
      !ok(options.settle_m)) {
    throw Error(
        "jump gate: sigmas, min_m, min_rad, the odometry errors and settle_m must be "
        "finite and >= 0");
  }
  if (options.settle_updates < 1) {
    throw Error("jump gate: settle_updates must be at least 1, got " +
                std::to_string(options.settle_updates));
  }
  if (options.settle_first_updates < 1) {
    throw Error("jump gate: settle_first_updates must be at least 1, got " +
                std::to_string(options.settle_first_updates));
  }
}

JumpGate::JumpGate(JumpGateOptions options) : options_(options) {
  validate(options_);
}

void JumpGate::reset() {
  reference_.reset();
  settling_.reset();
}

void JumpGate::reset(const GatedPose& reference) {
  reference_ = reference;
  settling_.reset();
}

bool JumpGate::consistent(const GatedPose& a, const GatedPose& b) const {
  const Pose2 moved = relative_pose(a.odometry, b.odometry);
  const Pose2 predicted = compose(a.pose, moved);
  const double driven = std::hypot(moved.x, moved.y);
  const double odometry_xy = options_.odometry_error_per_m * driven +
                             0.5 * options_.odometry_turn_error_per_m * driven * driven;
  const double odometry_theta = options_.odometry_turn_error_per_m * driven;
  const double var_xy = std::max(a.covariance(0, 0), a.covariance(1, 1)) +
                        std::max(b.covariance(0, 0), b.covariance(1, 1)) +
                        odometry_xy * odometry_xy;
  const double var_theta =
      a.covariance(2, 2) + b.covariance(2, 2) + odometry_theta * odometry_theta;
  const double allowed_xy = std::max(options_.min_m, options_.sigmas * std::sqrt(var_xy));
  const double allowed_theta = std::max(options_.min_rad, options_.sigmas * std::sqrt(var_theta));
  return std::hypot(b.pose.x - predicted.x, b.pose.y - predicted.y) <= allowed_xy &&
         std::abs(normalize_angle(b.pose.theta - predicted.theta)) <= allowed_theta;
}

bool JumpGate::admit(const GatedPose& answer) {
  if (reference_ ? consistent(*reference_, answer) : !options_.settle_first) {
    reference_ = answer;
    settling_.reset();
    return true;
  }
  if (settling_ && consistent(settling_->last, answer)) {
    const Pose2 moved = relative_pose(settling_->last.odometry, answer.odometry);
    settling_->driven_m += std::hypot(moved.x, moved.y);
    settling_->updates += 1;
    settling_->last = answer;
  } else {
    settling_ = Settling{answer};
  }
  const int updates = reference_ ? options_.settle_updates : options_.settle_first_updates;
  if (settling_->driven_m >= options_.settle_m && settling_->updates >= updates) {
    reference_ = answer;
    settling_.reset();
    return true;
  }
  return false;
}

}  // namespace gridloc
