// The Localizer's windows: where a tracked place is looked for, on the coarse copy and at the
// map's cell, and how the odometry's prior weighs what a window holds.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/engine/localizer/place_prior.hpp"

namespace gridloc {

bool Localizer::on_map(const Pose2& pose) const {
  const OccupancyMap& map = estimator_.map();
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(local.x, local.y);
  return map.geometry.contains(cell.ix, cell.iy);
}

Estimate Localizer::search_window(const Observation& observation, const SearchWindow& window,
                                  const Eigen::Matrix3d& covariance,
                                  std::vector<LookAlike>* look_alikes) const {
  const double cell = coarse_ ? coarse_->options().resolution : 0.0;
  if (!coarse_ || window.half_xy <= 3.0 * cell || !coarse_contains(window.center)) {
    return estimator_.estimate(observation, window);
  }
  // A wide window: its best place on the coarse copy, then within two coarse cells of it on
  // the tracker's grids; and within two coarse cells of the centre (the coarse copy may
  // blur a near place away).
  SearchWindow wide = window;
  wide.step_xy = cell;
  wide.step_theta = std::max(window.step_theta, coarse_->global_window(observation).step_theta);
  const bool very_wide =
      window.half_xy > options_.wide_window_m || window.half_theta > options_.wide_window_rad;
  const int peaks = look_alikes && very_wide ? options_.hypothesis_set.max_hypotheses : 1;
  const Estimate rough = coarse_->estimate(observation, wide, peaks);
  SearchWindow near = window;
  near.half_xy = 2.0 * cell;
  near.half_theta = std::min(window.half_theta, options_.wide_window_rad);
  Estimate at_centre = estimator_.estimate(observation, near);
  near.half_theta =
      std::min(window.half_theta, std::max(2.0 * wide.step_theta, options_.min_half_theta));
  if (!on_map(rough.pose)) return at_centre;  // the coarse copy's rim
  near.center = rough.pose;
  Estimate at_rough = estimator_.estimate(observation, near);
  // The far place must explain the scan better by more than the odometry's doubt of it and
  // score clearly more (a corridor turned round or slid along reads nearly the same).
  const PlacePrior prior = place_prior(window.center, covariance, window.step_theta);
  const bool far_wins = at_rough.score > (1.0 + options_.far_place_margin) * at_centre.score &&
                        posterior(at_rough, prior) > posterior(at_centre, prior);
  Estimate best = far_wins ? at_rough : at_centre;
  if (peaks > 1) *look_alikes = other_places(rough, best, prior);
  return best;
}

Localizer::PlacePrior Localizer::place_prior(const Pose2& carried,
                                             const Eigen::Matrix3d& covariance,
                                             double step_theta) const {
  const double cell = estimator_.options().resolution;
  return {carried, covariance, Eigen::Vector3d(cell * cell, cell * cell, step_theta * step_theta)};
}

double Localizer::posterior(const Estimate& e, const PlacePrior& prior) const {
  return options_.weights.evidence_per_scan * e.normalized_score +
         log_prior(e.pose, prior.carried, prior.covariance, prior.floor);
}

double Localizer::max_window_turn() const {
  return std::min(options_.max_half_theta, std::numbers::pi);
}

bool Localizer::coarse_contains(const Pose2& pose) const {
  const PaddedGrid& grid = coarse_->level(0);
  const double cell = coarse_->options().resolution;
  const Pose2 local = estimator_.map().geometry.to_grid_frame(pose);
  const double ix = std::floor(local.x / cell), iy = std::floor(local.y / cell);
  return ix >= 0.0 && iy >= 0.0 && ix < grid.width && iy < grid.height;
}

std::vector<LookAlike> Localizer::other_places(const Estimate& rough, const Estimate& chosen,
                                               const PlacePrior& prior) const {
  const HypothesisSetOptions& set = options_.hypothesis_set;
  const double chosen_prior = log_prior(chosen.pose, prior.carried, prior.covariance, prior.floor);
  std::vector<LookAlike> others;
  for (const Hypothesis& peak : rough.alternatives) {
    const Pose2& pose = peak.pose;
    const bool apart = std::hypot(pose.x - chosen.pose.x, pose.y - chosen.pose.y) > set.merge_xy ||
                       std::abs(normalize_angle(pose.theta - chosen.pose.theta)) > set.merge_theta;
    const bool kept = apart && peak.score >= options_.split_ratio * rough.score;
    if (!kept || !on_map(pose)) continue;
    others.push_back(
        {pose, log_prior(pose, prior.carried, prior.covariance, prior.floor) - chosen_prior});
  }
  return others;
}

Estimate Localizer::best_near(const Pose2& pose, const Observation& observation,
                              const SearchWindow& global, double half_theta) const {
  SearchWindow near;
  near.center = pose;
  near.step_xy = estimator_.options().resolution;
  near.step_theta = global.step_theta;
  near.half_xy = 2.0 * near.step_xy;
  near.half_theta = std::max(half_theta, 2.0 * near.step_theta);
  return estimator_.estimate(observation, near, 1);
}

/// The heading step is the global window's (5 deg for sonar; for a scan, about a cell at its
/// farthest return).
SearchWindow Localizer::window_around(const TrackedHypothesis& hypothesis,
                                      const SearchWindow& global) const {
  const Eigen::Matrix3d& covariance = hypothesis.covariance;
  const double sigma_xy = std::sqrt(std::max(covariance(0, 0), covariance(1, 1)));
  SearchWindow window;
  window.center = hypothesis.pose;
  window.step_xy = estimator_.options().resolution;
  window.step_theta = global.step_theta;
  // A place its last window missed is looked for twice as wide (further: the re-search).
  const double widen = hypothesis.misses > 0 ? 2.0 : 1.0;
  window.half_xy = std::clamp(options_.prior_sigmas * sigma_xy,
                              std::min(widen * options_.min_half_xy_m, options_.max_half_xy_m),
                              options_.max_half_xy_m);
  window.half_theta =
      std::clamp(options_.prior_sigmas * std::sqrt(covariance(2, 2)),
                 std::min(widen * options_.min_half_theta, max_window_turn()), max_window_turn());
  return window;
}

}  // namespace gridloc
