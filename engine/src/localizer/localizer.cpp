// The Localizer facade: odometry and sonar firings in, the current Estimate out.
#include "gridloc/engine/localizer/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/driver_readings.hpp"

namespace gridloc {
namespace {

/// The search options with the reach raised to cover every firing of the drive window: a
/// re-mounted sonar lies at most the path's length farther out than on the robot.
CorrelationOptions with_drive_reach(const LocalizerOptions& options, const SonarRing& ring) {
  if (!(options.drive.max_distance_m >= 0.0) || !std::isfinite(options.drive.max_distance_m)) {
    throw Error("localizer options: drive.max_distance_m must be finite and >= 0");
  }
  CorrelationOptions correlation = options.correlation;
  correlation.reach_m = std::max(correlation.reach_m, ring.reach() + options.drive.max_distance_m);
  return correlation;
}

/// Throws unless the window options are usable.
void check_options(const LocalizerOptions& options) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  const auto non_negative = [](double v) { return v >= 0.0 && std::isfinite(v); };
  if (!positive(options.prior_sigmas) || !non_negative(options.odometry_error_per_m) ||
      !non_negative(options.odometry_turn_error_per_m) || !positive(options.min_half_xy_m) ||
      !(options.max_half_xy_m >= options.min_half_xy_m) || !std::isfinite(options.max_half_xy_m) ||
      !(options.min_half_theta > 0.0 && options.min_half_theta <= std::numbers::pi)) {
    throw Error(
        "localizer options: prior_sigmas, min_half_xy_m and min_half_theta (<= pi) must be > 0, "
        "the odometry errors >= 0 and max_half_xy_m >= min_half_xy_m, all finite");
  }
}

bool finite(const Pose2& pose) {
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
}

/// Drops the firings the window no longer keeps (the latest is always kept).
void prune_drive(std::vector<OdometryFiring>& drive, const SonarRing& ring,
                 const DriveWindowOptions& window) {
  const std::size_t kept = fuse_firings(ring, drive, window).firings;
  drive.erase(drive.begin(), drive.end() - static_cast<std::ptrdiff_t>(kept));
}

}  // namespace

Localizer::Localizer(OccupancyMap map, SonarRing ring, LocalizerOptions options)
    : options_(options), estimator_(std::move(map), ring, with_drive_reach(options, ring)) {
  check_options(options_);
  validate(options_.drive);
}

void Localizer::reset() {
  std::unique_lock lock(mutex_);
  state_ = LocalizerState{};
}

void Localizer::set_prior(const Pose2& pose, const Eigen::Matrix3d& covariance) {
  if (!finite(pose)) throw Error("localizer: the prior pose must be finite");
  for (int i = 0; i < 3; ++i) {
    if (!(covariance(i, i) >= 0.0) || !std::isfinite(covariance(i, i))) {
      throw Error("localizer: the prior covariance's diagonal must be finite and >= 0");
    }
  }
  std::unique_lock lock(mutex_);
  state_.prior = pose;
  state_.prior_covariance = covariance;
  state_.prior_odometry = state_.odometry.value_or(Pose2{});
}

void Localizer::add_odometry(const Pose2& odometry) {
  if (!finite(odometry)) throw Error("localizer: odometry pose must be finite");
  std::unique_lock lock(mutex_);
  state_.odometry = odometry;
}

void Localizer::add_observation(double time_s, const std::vector<double>& driver_ranges) {
  if (!std::isfinite(time_s)) throw Error("localizer: observation time must be finite");
  const DriverReadings readings = from_driver(estimator_.ring(), driver_ranges);
  LocalizerState next;
  {
    std::shared_lock lock(mutex_);  // the only writer: the state cannot change meanwhile
    next = state_;
  }
  // The search runs without the lock, so readers get the previous estimate meanwhile.
  next.drive.push_back({next.odometry.value_or(Pose2{}), readings.ranges, readings.rejected});
  prune_drive(next.drive, estimator_.ring(), options_.drive);
  const FusedFirings fused = fuse_firings(estimator_.ring(), next.drive, options_.drive);
  const Observation observation{fused.ranges, std::nullopt, fused.rejected, fused.ring};
  const Estimate e = estimator_.estimate(observation, window_now(next));
  if (e.verdict == Verdict::Localized) {
    next.prior = e.pose;
    next.prior_covariance = e.covariance;
    next.prior_odometry = next.drive.back().odometry;
  }
  next.estimate = e;
  std::unique_lock lock(mutex_);
  state_ = std::move(next);
}

Estimate Localizer::estimate() const {
  std::shared_lock lock(mutex_);
  if (!state_.estimate) throw Error("localizer: no estimate yet (add an observation first)");
  return *state_.estimate;
}

/// The window around the prior carried to the latest odometry pose, grown by the odometry's
/// error since; the global window without a prior or when that grows past max_half_xy_m.
SearchWindow Localizer::window_now(const LocalizerState& state) const {
  const Observation probe{std::vector<double>(estimator_.ring().sonars.size(), 0.0)};
  if (!state.prior) return estimator_.global_window(probe);
  const Pose2 odometry = state.drive.back().odometry;
  const Pose2 moved = relative_pose(state.prior_odometry, odometry);
  const double distance = std::hypot(moved.x, moved.y);
  const double sigma_xy =
      std::sqrt(std::max(state.prior_covariance(0, 0), state.prior_covariance(1, 1)));
  const double half_xy =
      options_.prior_sigmas * sigma_xy + options_.odometry_error_per_m * distance;
  if (half_xy > options_.max_half_xy_m) return estimator_.global_window(probe);
  SearchWindow window;
  window.center = compose(*state.prior, moved);
  window.step_xy = estimator_.options().resolution;
  window.half_xy = std::max(half_xy, options_.min_half_xy_m);
  const double half_theta = options_.prior_sigmas * std::sqrt(state.prior_covariance(2, 2)) +
                            options_.odometry_turn_error_per_m * distance;
  window.half_theta = std::clamp(half_theta, options_.min_half_theta, std::numbers::pi);
  return window;
}

}  // namespace gridloc
