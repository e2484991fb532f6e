// The Localizer facade: odometry and sonar firings or laser scans in, the current Estimate
// out, through a set of hypotheses that survive motion.
#include "gridloc/engine/localizer/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/driver_readings.hpp"

namespace gridloc {
namespace {

/// Throws naming `field` and its value unless `ok`.
void require(bool ok, const char* field, double value, const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message << "localizer options: " << field << " = " << value << " " << rule;
  throw Error(message.str());
}

/// Throws unless the options are usable; runs before the global grids are built.
const LocalizerOptions& checked(const LocalizerOptions& options) {
  const auto finite_at_least = [](double v, double low) { return std::isfinite(v) && v >= low; };
  require(finite_at_least(options.prior_sigmas, 0.0) && options.prior_sigmas > 0.0, "prior_sigmas",
          options.prior_sigmas, "must be finite and > 0");
  require(finite_at_least(options.odometry_error_per_m, 0.0), "odometry_error_per_m",
          options.odometry_error_per_m, "must be finite and >= 0");
  require(finite_at_least(options.odometry_turn_error_per_m, 0.0), "odometry_turn_error_per_m",
          options.odometry_turn_error_per_m, "must be finite and >= 0");
  require(finite_at_least(options.min_half_xy_m, 0.0) && options.min_half_xy_m > 0.0,
          "min_half_xy_m", options.min_half_xy_m, "must be finite and > 0");
  require(finite_at_least(options.max_half_xy_m, options.min_half_xy_m), "max_half_xy_m",
          options.max_half_xy_m, "must be finite and >= min_half_xy_m");
  require(options.min_half_theta > 0.0 && options.min_half_theta <= std::numbers::pi,
          "min_half_theta", options.min_half_theta, "must lie in (0, pi]");
  require(options.misses_before_global >= 1, "misses_before_global", options.misses_before_global,
          "must be at least 1");
  require(finite_at_least(options.max_range_slack_m, 0.0), "max_range_slack_m",
          options.max_range_slack_m, "must be finite and >= 0");
  require(finite_at_least(options.reseed_after_m, 0.0), "reseed_after_m", options.reseed_after_m,
          "must be finite and >= 0");
  validate(options.drive);
  validate(options.hypothesis_set);
  return options;
}

/// The search options with the reach raised to cover every firing of the drive window: a
/// re-mounted sonar lies at most the path's length farther out than on the robot.
CorrelationOptions with_drive_reach(const LocalizerOptions& options, const SonarRing& ring) {
  CorrelationOptions correlation = options.correlation;
  correlation.reach_m = std::max(correlation.reach_m, ring.reach() + options.drive.max_distance_m);
  return correlation;
}

/// The search options for a laser: scans as rigid points, reaching the laser's range from
/// anywhere along the drive window.
CorrelationOptions with_laser_reach(const LocalizerOptions& options, const LaserSensor& laser) {
  validate(laser);
  CorrelationOptions correlation = options.correlation;
  correlation.scan = laser.model;
  correlation.reach_m =
      std::max(correlation.reach_m, laser.max_range + std::hypot(laser.mount.x, laser.mount.y) +
                                        options.drive.max_distance_m);
  return correlation;
}

bool finite(const Pose2& pose) {
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
}

/// Keeps the latest `kept` readings of a drive (the ones the window kept when fusing).
template <class Reading>
void keep_latest(std::vector<Reading>& drive, std::size_t kept) {
  drive.erase(drive.begin(), drive.end() - static_cast<std::ptrdiff_t>(kept));
}

/// The scan with returns at or beyond the laser's max range read as no return.
RangeScan clipped(const RangeScan& scan, const LaserSensor& laser) {
  RangeScan clipped = scan;
  clipped.max_range = std::min(scan.max_range, laser.max_range);
  for (double& r : clipped.ranges) r = std::min(r, clipped.max_range);
  return clipped;
}

/// Whether a world pose lies on the map's grid.
bool on_map(const OccupancyMap& map, const Pose2& pose) {
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(local.x, local.y);
  return map.geometry.contains(cell.ix, cell.iy);
}

/// The state after an observation's estimate: the set now refers to `taken_at`, and the
/// `not localized` answers in a row are counted.
void take_estimate(LocalizerState& state, const Estimate& e, const Pose2& taken_at) {
  state.estimate = e;
  state.set_odometry = taken_at;
  state.travelled_m = 0.0;
  state.misses = e.verdict == Verdict::NotLocalized ? state.misses + 1 : 0;
}

}  // namespace

Localizer::Localizer(OccupancyMap map, SonarRing ring, LocalizerOptions options)
    : options_(checked(options)),
      estimator_(std::move(map), ring, with_drive_reach(options_, ring)) {}

Localizer::Localizer(OccupancyMap map, LaserSensor laser, LocalizerOptions options)
    : options_(checked(options)),
      laser_(laser),
      estimator_(std::move(map), with_laser_reach(options_, laser)) {}

void validate(const LaserSensor& laser) {
  if (!finite(laser.mount)) throw Error("laser: the mount pose must be finite");
  if (!(laser.max_range > 0.0) || !std::isfinite(laser.max_range)) {
    throw Error("laser: max_range must be finite and > 0, got " + std::to_string(laser.max_range));
  }
  validate(laser.model);
  if (laser.model.model == ScanModel::Rays) {
    throw Error("laser: the ray model has no rigid points; use hits or samples");
  }
}

void Localizer::reset() {
  std::unique_lock lock(mutex_);
  const std::optional<Pose2> odometry = state_.odometry;
  state_ = LocalizerState{};
  state_.odometry = odometry;
}

void Localizer::set_prior(const Pose2& pose, const Eigen::Matrix3d& covariance) {
  if (!finite(pose)) throw Error("localizer: the prior pose must be finite");
  if (!covariance.allFinite() || (covariance.diagonal().array() < 0.0).any()) {
    throw Error("localizer: the prior covariance must be finite with a diagonal >= 0");
  }
  std::unique_lock lock(mutex_);
  state_.set = {};
  state_.set.hypotheses.push_back({pose, covariance, 0.0, Estimate{}});
  state_.set_odometry = state_.odometry.value_or(Pose2{});
  state_.travelled_m = 0.0;
  state_.misses = 0;
}

void Localizer::add_odometry(const Pose2& odometry) {
  if (!finite(odometry)) throw Error("localizer: odometry pose must be finite");
  std::unique_lock lock(mutex_);
  if (state_.odometry) {
    const Pose2 step = relative_pose(*state_.odometry, odometry);
    state_.travelled_m += std::hypot(step.x, step.y);
  }
  state_.odometry = odometry;
}

void Localizer::add_observation(double time_s, const std::vector<double>& driver_ranges) {
  if (!std::isfinite(time_s)) throw Error("localizer: observation time must be finite");
  if (laser_) throw Error("localizer: built for a laser; give scans, not sonar ranges");
  const DriverReadings readings =
      from_driver(estimator_.ring(), driver_ranges, options_.max_range_slack_m);
  LocalizerState next;
  {
    std::shared_lock lock(mutex_);
    next = state_;
  }
  const Pose2 taken_at = next.odometry.value_or(Pose2{});
  next.drive.push_back({taken_at, readings.ranges, readings.rejected});
  const FusedFirings fused = fuse_firings(estimator_.ring(), next.drive, options_.drive);
  keep_latest(next.drive, fused.firings);
  localize(std::move(next), taken_at,
           Observation{fused.ranges, std::nullopt, fused.rejected, fused.ring});
}

void Localizer::add_observation(double time_s, const RangeScan& scan) {
  if (!std::isfinite(time_s)) throw Error("localizer: observation time must be finite");
  if (!laser_) throw Error("localizer: built for a sonar ring; give sonar ranges, not a scan");
  validate(scan);
  LocalizerState next;
  {
    std::shared_lock lock(mutex_);
    next = state_;
  }
  const Pose2 taken_at = next.odometry.value_or(Pose2{});
  next.scans.push_back({taken_at, clipped(scan, *laser_)});
  const FusedScans fused = fuse_scans(next.scans, laser_->mount, laser_->model, options_.drive);
  keep_latest(next.scans, fused.scans);
  Observation observation;
  observation.points = fused.points;
  localize(std::move(next), taken_at, observation);
}

void Localizer::localize(LocalizerState next, const Pose2& taken_at,
                         const Observation& observation) {
  const double travelled_before = next.travelled_m;
  // The searches run without the lock, so readers get the previous estimate meanwhile.
  next.since_global_m += next.travelled_m;
  const bool ambiguous = next.estimate && next.estimate->verdict == Verdict::Ambiguous;
  const bool lost = next.misses >= options_.misses_before_global;
  std::vector<TrackedHypothesis> candidates = follow(next, taken_at, observation);
  std::optional<Estimate> global;
  if (candidates.empty() || lost || (ambiguous && next.since_global_m >= options_.reseed_after_m)) {
    // A lone track, unsure but not lost: only seeds near it join (odometry vouches for that
    // place; a look-alike across the building does not displace the track).
    const bool near_only = next.set.hypotheses.size() == 1 && !candidates.empty() && !lost;
    global = search_globally(observation, candidates, near_only);
    next.since_global_m = 0.0;
    next.misses = 0;
  }
  merge_and_prune(candidates, options_.hypothesis_set);
  next.set = {std::move(candidates)};
  const Estimate e = next.set.hypotheses.empty()
                         ? *global  // the global search was run and is not localized
                         : set_estimate(next.set);
  take_estimate(next, e, taken_at);
  std::unique_lock lock(mutex_);
  // Odometry that arrived during the search is kept, with the path it added.
  next.travelled_m += state_.travelled_m - travelled_before;
  next.odometry = state_.odometry;
  state_ = std::move(next);
}

Estimate Localizer::search_globally(const Observation& observation,
                                    std::vector<TrackedHypothesis>& candidates,
                                    bool near_only) const {
  const HypothesisSetOptions& set_options = options_.hypothesis_set;
  const Estimate global = estimator_.estimate(observation, estimator_.global_window(observation),
                                              set_options.max_hypotheses + 1);
  if (global.verdict == Verdict::NotLocalized) return global;
  const std::vector<TrackedHypothesis> tracked = candidates;
  const auto near_tracked = [&](const TrackedHypothesis& seed) {
    return std::any_of(tracked.begin(), tracked.end(), [&](const TrackedHypothesis& h) {
      return std::hypot(seed.pose.x - h.pose.x, seed.pose.y - h.pose.y) <= options_.max_half_xy_m;
    });
  };
  for (TrackedHypothesis& seed : seed_hypotheses(global, set_options).hypotheses) {
    if (!near_only || near_tracked(seed)) candidates.push_back(std::move(seed));
  }
  return global;
}

std::vector<TrackedHypothesis> Localizer::follow(const LocalizerState& next, const Pose2& taken_at,
                                                 const Observation& observation) const {
  const Pose2 moved = relative_pose(next.set_odometry, taken_at);
  const SearchWindow global = estimator_.global_window(observation);
  std::vector<TrackedHypothesis> followed;
  for (const TrackedHypothesis& hypothesis : next.set.hypotheses) {
    const std::optional<SearchWindow> window =
        window_around(hypothesis, moved, next.travelled_m, global);
    if (!window) continue;
    Estimate e = estimator_.estimate(observation, *window);
    // A window that explains nothing does not move the hypothesis (its winner is noise).
    const bool lost = e.verdict == Verdict::NotLocalized;
    const Pose2 pose = lost ? window->center : e.pose;
    const Eigen::Matrix3d covariance = lost ? hypothesis.covariance : e.covariance;
    followed.push_back({pose, covariance, e.score, std::move(e)});
  }
  return followed;
}

Estimate Localizer::estimate() const {
  std::shared_lock lock(mutex_);
  if (!state_.estimate) throw Error("localizer: no estimate yet (add an observation first)");
  return *state_.estimate;
}

/// The heading step is the global window's (5 deg for sonar; for a scan, about a cell at its
/// farthest return).
std::optional<SearchWindow> Localizer::window_around(const TrackedHypothesis& hypothesis,
                                                     const Pose2& moved, double travelled_m,
                                                     const SearchWindow& global) const {
  const Eigen::Matrix3d& covariance = hypothesis.covariance;
  const double sigma_xy = std::sqrt(std::max(covariance(0, 0), covariance(1, 1)));
  const double half_xy =
      options_.prior_sigmas * sigma_xy + options_.odometry_error_per_m * travelled_m;
  SearchWindow window;
  window.center = compose(hypothesis.pose, moved);
  if (half_xy > options_.max_half_xy_m || !on_map(estimator_.map(), window.center)) {
    return std::nullopt;
  }
  window.step_xy = estimator_.options().resolution;
  window.step_theta = global.step_theta;
  window.half_xy = std::max(half_xy, options_.min_half_xy_m);
  const double half_theta = options_.prior_sigmas * std::sqrt(covariance(2, 2)) +
                            options_.odometry_turn_error_per_m * travelled_m;
  window.half_theta = std::clamp(half_theta, options_.min_half_theta, std::numbers::pi);
  return window;
}

}  // namespace gridloc
