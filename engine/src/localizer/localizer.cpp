// The Localizer facade: odometry and sonar firings or laser scans in, the current Estimate
// out, through a set of hypotheses that survive motion.
#include "gridloc/engine/localizer/localizer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/driver_readings.hpp"

namespace gridloc {
namespace {

constexpr const char* kOwner = "localizer options";

/// Throws naming `field` and its value unless `ok`.
void require(bool ok, const char* field, double value, const char* rule) {
  require_option(ok, kOwner, field, value, rule);
}

/// Throws naming `field` unless `value` lies in [0, 1].
void require_share(double value, const char* field) {
  gridloc::require_share(value, kOwner, field);
}

/// Throws naming `field` unless `value` is finite and >= 0.
void require_non_negative(double value, const char* field) {
  gridloc::require_non_negative(value, kOwner, field);
}

/// Throws unless the options are usable; runs before the global grids are built.
const LocalizerOptions& checked(const LocalizerOptions& options) {
  const auto finite_at_least = [](double v, double low) { return std::isfinite(v) && v >= low; };
  require(finite_at_least(options.prior_sigmas, 0.0) && options.prior_sigmas > 0.0, "prior_sigmas",
          options.prior_sigmas, "must be finite and > 0");
  require_non_negative(options.odometry_error_per_m, "odometry_error_per_m");
  require_non_negative(options.odometry_turn_error_per_m, "odometry_turn_error_per_m");
  require(finite_at_least(options.min_half_xy_m, 0.0) && options.min_half_xy_m > 0.0,
          "min_half_xy_m", options.min_half_xy_m, "must be finite and > 0");
  require(finite_at_least(options.max_half_xy_m, options.min_half_xy_m), "max_half_xy_m",
          options.max_half_xy_m, "must be finite and >= min_half_xy_m");
  require(options.min_half_theta > 0.0 && options.min_half_theta <= std::numbers::pi,
          "min_half_theta", options.min_half_theta, "must lie in (0, pi]");
  require(finite_at_least(options.max_half_theta, options.min_half_theta), "max_half_theta",
          options.max_half_theta, "must be finite and >= min_half_theta");
  require(options.misses_before_global >= 1, "misses_before_global", options.misses_before_global,
          "must be at least 1");
  require_non_negative(options.max_range_slack_m, "max_range_slack_m");
  require_non_negative(options.reseed_after_m, "reseed_after_m");
  require(options.odometry_score_slack >= 0.0 && options.odometry_score_slack < 1.0,
          "odometry_score_slack", options.odometry_score_slack, "must lie in [0, 1)");
  require(options.split_ratio > 0.0 && options.split_ratio <= 1.0, "split_ratio",
          options.split_ratio, "must lie in (0, 1]");
  require_non_negative(options.far_place_margin, "far_place_margin");
  require(finite_at_least(options.wide_window_m, 0.0) && options.wide_window_m > 0.0,
          "wide_window_m", options.wide_window_m, "must be finite and > 0");
  require(options.wide_window_rad > 0.0 && std::isfinite(options.wide_window_rad),
          "wide_window_rad", options.wide_window_rad, "must be finite and > 0");
  require_non_negative(options.step_min_m, "step_min_m");
  require_non_negative(options.step_min_rad, "step_min_rad");
  require_non_negative(options.localized_sigma_m, "localized_sigma_m");
  require_non_negative(options.laser_localized_sigma_m, "laser_localized_sigma_m");
  require_non_negative(options.localized_sigma_rad, "localized_sigma_rad");
  require_share(options.miss_fit_ratio, "miss_fit_ratio");
  require_share(options.weak_fit_ratio, "weak_fit_ratio");
  require_share(options.prior_fit_ratio, "prior_fit_ratio");
  require_share(options.localized_fit_ratio, "localized_fit_ratio");
  require(options.first_drop_ratio > 0.0 && options.first_drop_ratio <= 1.0, "first_drop_ratio",
          options.first_drop_ratio, "must lie in (0, 1]");
  require_non_negative(options.reported_floor_m, "reported_floor_m");
  require_non_negative(options.reported_floor_rad, "reported_floor_rad");
  require_non_negative(options.fused_window_error_m, "fused_window_error_m");
  require_share(options.light_place_weight, "light_place_weight");
  require_share(options.turn_fit_ratio, "turn_fit_ratio");
  require_non_negative(options.odometry_turn_error_per_rad, "odometry_turn_error_per_rad");
  require_non_negative(options.kept_heading_sigmas, "kept_heading_sigmas");
  require(options.kept_max_half_theta >= 0.0 && options.kept_max_half_theta <= std::numbers::pi,
          "kept_max_half_theta", options.kept_max_half_theta, "must lie in [0, pi]");
  validate(options.drive);
  validate(options.hypothesis_set);
  validate(options.weights);
  validate(options.jump_gate);
  validate(options.research);
  return options;
}

/// The search options with the reach raised to cover every firing of the drive window: a
/// re-mounted sonar lies at most the path's length farther out than on the robot.
CorrelationOptions with_drive_reach(const LocalizerOptions& options, const SonarRing& ring) {
  CorrelationOptions correlation = options.correlation;
  correlation.reach_m = std::max(correlation.reach_m, ring.reach() + options.drive.max_distance_m);
  return correlation;
}

/// The smallest share of a search's best that a place it reports must score to be read: a
/// seed (HypothesisSetOptions::drop_ratio, first_drop_ratio) or a wide window's look-alike
/// (split_ratio).
double places_floor(const LocalizerOptions& options) {
  return std::min(
      {options.hypothesis_set.drop_ratio, options.first_drop_ratio, options.split_ratio, 0.99});
}

/// The search options for a laser: scans as rigid points, reaching the laser's range from
/// anywhere along the drive window; the hypotheses above a floor, in one search.
CorrelationOptions with_laser_reach(const LocalizerOptions& options, const LaserSensor& laser) {
  validate(laser);
  CorrelationOptions correlation =
      laser.tracking_field ? with_laser_tracking_grid(options.correlation) : options.correlation;
  correlation.scan = laser.model;
  // A window's second peak matters to its confidence only above the default floor, and its
  // places (a search without a coarse copy) only above places_floor.
  if (correlation.second_peak_floor <= 0.0) {
    correlation.second_peak_floor =
        std::min(CorrelationOptions{}.second_peak_floor, places_floor(options));
  }
  correlation.reach_m =
      std::max(correlation.reach_m, laser.max_range + std::hypot(laser.mount.x, laser.mount.y) +
                                        options.drive.max_distance_m);
  // With every whole-map search on the coarse copy, the tracker's own grids serve windows of
  // at most max_half_xy_m: a bound pyramid that deep answers them as a deeper one does.
  const bool coarse_searches =
      options.research.resolution > correlation.resolution && options.research.coarse_first_search;
  if (coarse_searches && correlation.max_bound_depth == 0) {
    SearchWindow widest;
    widest.half_xy = options.max_half_xy_m;
    widest.step_xy = correlation.resolution;
    correlation.max_bound_depth = window_bound_depth(widest);
  }
  return correlation;
}

/// Why the answer `e` from the weighted `places` (heaviest first) is not `localized`.
HeldBack held_back(const std::vector<TrackedHypothesis>& places, const Estimate& e,
                   const HypothesisWeightOptions& weights) {
  if (e.verdict != Verdict::NotLocalized) return HeldBack::None;
  if (places.empty()) return HeldBack::NoPlace;
  const TrackedHypothesis& heaviest = places.front();
  if (heaviest.newcomer && heaviest.driven_m < weights.newcomer_settle_m) return HeldBack::Newcomer;
  return heaviest.held_back;
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

/// The state after an observation's estimate: the set now refers to `taken_at`.
void take_estimate(LocalizerState& state, const Estimate& e, const Pose2& taken_at) {
  state.estimate = e;
  state.set_odometry = taken_at;
  state.travelled_m = 0.0;
  state.turned_rad = 0.0;
}

}  // namespace

Localizer::Localizer(OccupancyMap map, SonarRing ring, LocalizerOptions options)
    : options_(checked(options)),
      estimator_(std::move(map), ring, with_drive_reach(options_, ring)) {
  state_.gate = JumpGate(options_.jump_gate);
}

Localizer::Localizer(OccupancyMap map, LaserSensor laser, LocalizerOptions options)
    : options_(checked(options)),
      laser_(laser),
      estimator_(std::move(map), with_laser_reach(options_, laser)) {
  state_.gate = JumpGate(options_.jump_gate);
  if (options_.research.resolution > estimator_.options().resolution) {
    CorrelationOptions coarse = estimator_.options();
    coarse.resolution = options_.research.resolution;
    coarse.max_bound_depth = options_.correlation.max_bound_depth;  // it searches the whole map
    // Its searches' places are read from the smallest share of the best any reader keeps
    // (the seeds, drop_ratio; a wide window's look-alikes, split_ratio): branch and bound
    // finds every one above it in its one search, where a floor of 0 searched again for each.
    coarse.second_peak_floor = places_floor(options_);
    coarse_.emplace(estimator_.map(), coarse);
  }
}

const CorrelationEstimator& Localizer::search_estimator(bool first) const {
  const bool coarse = coarse_ && (!first || options_.research.coarse_first_search);
  return coarse ? *coarse_ : estimator_;
}

CorrelationOptions with_laser_tracking_grid(CorrelationOptions options) {
  options.global = GlobalModel::LikelihoodField;
  options.field.sigma_m = 0.05;
  options.field.cutoff_m = 0.15;
  options.field.free_value = 0.0;
  return options;
}

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
  state_.gate = JumpGate(options_.jump_gate);
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
  state_.turned_rad = 0.0;
  state_.search.reset();
  state_.gate.reset({pose, covariance, state_.set_odometry});
}

void Localizer::add_odometry(const Pose2& odometry) {
  if (!finite(odometry)) throw Error("localizer: odometry pose must be finite");
  std::unique_lock lock(mutex_);
  if (state_.odometry) {
    const Pose2 step = relative_pose(*state_.odometry, odometry);
    state_.travelled_m += std::hypot(step.x, step.y);
    state_.turned_rad += std::abs(step.theta);
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
  DriveWindowOptions drive = options_.drive;
  if (!laser_->fuse_drive) drive.max_firings = 1;
  const FusedScans fused = fuse_scans(next.scans, laser_->mount, laser_->model, drive);
  keep_latest(next.scans, fused.scans);
  Observation observation;
  observation.points = fused.points;
  localize(std::move(next), taken_at, observation);
}

void Localizer::localize(LocalizerState next, const Pose2& taken_at,
                         const Observation& observation) {
  // The searches run without the lock, so readers get the previous estimate meanwhile.
  const double travelled_before = next.travelled_m, turned_before = next.turned_rad;
  next.since_global_m += next.travelled_m;
  next.since_weights_m += next.travelled_m;
  next.since_weights_rad += next.turned_rad;
  std::vector<TrackedHypothesis> tracked = follow(next, taken_at, observation);
  const HypothesisWeightOptions& weights = options_.weights;
  if (!next.estimate || next.since_weights_m >= weights.update_min_m ||
      next.since_weights_rad >= weights.update_min_rad) {
    add_evidence(tracked, weights);  // a standstill repeats the view: no new evidence
    next.since_weights_m = next.since_weights_rad = 0.0;
  }
  next.status = {};
  const std::optional<Estimate> searched = advance_search(next, tracked, taken_at, observation);
  merge_and_prune_weighted(tracked, options_.hypothesis_set, weights);
  next.set = {std::move(tracked)};
  Estimate e = next.set.hypotheses.empty() ? searched.value_or(next.estimate.value_or(Estimate{}))
                                           : weighted_estimate(next.set.hypotheses, weights);
  if (next.set.hypotheses.empty()) e.verdict = Verdict::NotLocalized;
  next.status.held_back = held_back(next.set.hypotheses, e, weights);
  const bool had_reference = next.gate.has_reference();
  if (e.verdict == Verdict::Localized && !next.gate.admit({e.pose, e.covariance, taken_at})) {
    e.verdict = Verdict::NotLocalized;
    (had_reference ? next.status.jump_rejected : next.status.confirming) = true;
    next.status.held_back = had_reference ? HeldBack::JumpRejected : HeldBack::Confirming;
  }
  // After every decision, only what the caller reads grows; an estimate carried over from
  // the last update (no place left, no search) has its floor already.
  const bool carried_over = next.set.hypotheses.empty() && !searched;
  if (laser_ && !carried_over) {
    add_reported_floor(e, options_.reported_floor_m, options_.reported_floor_rad);
  }
  take_estimate(next, e, taken_at);
  std::unique_lock lock(mutex_);
  // Odometry that arrived during the search is kept, with the path it added.
  next.travelled_m += state_.travelled_m - travelled_before;
  next.turned_rad += state_.turned_rad - turned_before;
  next.odometry = state_.odometry;
  state_ = std::move(next);
}

std::vector<TrackedHypothesis> Localizer::follow(const LocalizerState& next, const Pose2& taken_at,
                                                 const Observation& observation) const {
  const Pose2 moved = relative_pose(next.set_odometry, taken_at);
  std::vector<TrackedHypothesis> followed;
  for (const TrackedHypothesis& hypothesis : next.set.hypotheses) {
    std::vector<LookAlike> look_alikes;
    const bool light = hypothesis.weight < options_.light_place_weight;
    std::optional<TrackedHypothesis> carried = follow_one(
        hypothesis, moved, next.travelled_m, observation, light ? nullptr : &look_alikes, !light);
    if (!carried) continue;
    // A place carried so far that its window spans look-alikes splits into them: the weights,
    // not this one scan, will say which it is; the odometry's prior gives each its start.
    for (const LookAlike& look_alike : look_alikes) {
      TrackedHypothesis split = *carried;
      split.pose = look_alike.pose;
      split.log_weight += look_alike.log_prior;
      const double cell = (coarse_ ? coarse_->options() : estimator_.options()).resolution;
      split.covariance = Eigen::Vector3d(cell * cell, cell * cell,
                                         options_.min_half_theta * options_.min_half_theta / 9.0)
                             .asDiagonal();
      split.confirmed = false;
      split.misses = 0;
      std::optional<TrackedHypothesis> placed =
          follow_one(split, Pose2{}, 0.0, observation, nullptr);
      if (!placed || takes_over_a_miss(*placed, *carried)) continue;
      followed.push_back(std::move(*placed));
    }
    followed.push_back(std::move(*carried));
  }
  return followed;
}

std::optional<TrackedHypothesis> Localizer::follow_one(TrackedHypothesis hypothesis,
                                                       const Pose2& moved, double travelled_m,
                                                       const Observation& observation,
                                                       std::vector<LookAlike>* look_alikes,
                                                       bool second_look) const {
  hypothesis.pose = compose(hypothesis.pose, moved);
  hypothesis.driven_m += travelled_m;
  if (!on_map(hypothesis.pose)) return std::nullopt;
  const double xy = options_.odometry_error_per_m * travelled_m +
                    0.5 * options_.odometry_turn_error_per_m * travelled_m * travelled_m;
  const double theta = options_.odometry_turn_error_per_m * travelled_m +
                       options_.odometry_turn_error_per_rad * std::abs(moved.theta);
  const double cap = options_.max_half_xy_m * options_.max_half_xy_m;  // a lost place's bound
  Eigen::Matrix3d& covariance = hypothesis.covariance;
  covariance(0, 0) = std::min(covariance(0, 0) + xy * xy, cap);
  covariance(1, 1) = std::min(covariance(1, 1) + xy * xy, cap);
  covariance(2, 2) =
      std::min(covariance(2, 2) + theta * theta, std::numbers::pi * std::numbers::pi);
  const SearchWindow global = estimator_.global_window(observation);
  SearchWindow window = window_around(hypothesis, global);
  Estimate e = search_window(observation, window, covariance, look_alikes);
  if (e.on_window_edge && hypothesis.confirmed && second_look) {
    // The best may lie beyond (a slip): look once more, twice as wide.
    window.half_xy =
        std::min(2.0 * window.half_xy, std::max(options_.max_half_xy_m, window.half_xy));
    window.half_theta = std::min(2.0 * window.half_theta, max_window_turn());
    e = search_window(observation, window, covariance);
  }
  place(hypothesis, e, observation, global, look_alikes);
  hypothesis.score = e.score;
  hypothesis.estimate = std::move(e);
  return hypothesis;
}

bool Localizer::takes_over_a_miss(const TrackedHypothesis& look_alike,
                                  const TrackedHypothesis& carried) const {
  return carried.misses > 0 && look_alike.held_back == HeldBack::Miss &&
         have_met(look_alike.pose, carried.pose, options_.hypothesis_set);
}

Estimate Localizer::estimate() const {
  std::shared_lock lock(mutex_);
  if (!state_.estimate) throw Error("localizer: no estimate yet (add an observation first)");
  return *state_.estimate;
}

LocalizerStatus Localizer::status() const {
  std::shared_lock lock(mutex_);
  return state_.status;
}

}  // namespace gridloc
