// How a window places a tracked place: a miss, a weak fit the odometry bears out, the
// window's winner, or the odometry's place the scan cannot tell from it; and when a step is
// more than the odometry allows.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/engine/localizer/place_prior.hpp"

namespace gridloc {
namespace {

/// The covariance of two independent Gaussian estimates of one pose combined (the Kalman
/// update's a - a (a + b)^-1 a). A whisker on the diagonal keeps a + b invertible when both
/// are certain along some direction (a zero prior covariance, a window without covariance
/// cells): the result is then certain there too, never NaN.
Eigen::Matrix3d fused(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d sum = a + b + 1e-15 * Eigen::Matrix3d::Identity();
  return a - a * sum.inverse() * a;
}

}  // namespace

void Localizer::place(TrackedHypothesis& hypothesis, Estimate& e, const Observation& observation,
                      const SearchWindow& global, std::vector<LookAlike>* look_alikes) const {
  // A window always finds something: one scoring far below the place's usual fit explains
  // nothing there (a miss), and does not move the place.
  const bool miss = hypothesis.usual_fit > 0.0
                        ? e.normalized_score < options_.miss_fit_ratio * hypothesis.usual_fit
                        : e.verdict == Verdict::NotLocalized;
  const bool after_a_miss = hypothesis.held_back == HeldBack::Miss;
  hypothesis.held_back = HeldBack::None;
  if (miss) {
    ++hypothesis.misses;
    if (!place_on_weak_fit(hypothesis, e, after_a_miss)) {
      e.verdict = Verdict::NotLocalized;
      hypothesis.held_back = HeldBack::Miss;
    }
    return;
  }
  hypothesis.misses = 0;
  const bool weak = e.normalized_score < options_.localized_fit_ratio * hypothesis.usual_fit;
  hypothesis.usual_fit = hypothesis.usual_fit > 0.0
                             ? 0.9 * hypothesis.usual_fit + 0.1 * e.normalized_score
                             : e.normalized_score;
  // Where the odometry carried it, or within two cells: when that scores as well as the
  // window's winner, the scan does not move the place (along a corridor it cannot).
  const Estimate near = best_near(hypothesis.pose, observation, global);
  const PlacePrior prior = place_prior(hypothesis.pose, hypothesis.covariance, global.step_theta);
  const bool fits_as_usual =
      near.normalized_score >= options_.prior_fit_ratio * hypothesis.usual_fit;
  const bool odometry_holds = near.score >= (1.0 - options_.odometry_score_slack) * e.score ||
                              (fits_as_usual && posterior(near, prior) >= posterior(e, prior));
  const bool same =
      std::hypot(near.pose.x - e.pose.x, near.pose.y - e.pose.y) <=
          2.0 * estimator_.options().resolution &&
      std::abs(normalize_angle(near.pose.theta - e.pose.theta)) <= 2.0 * global.step_theta;
  const bool takes = e.verdict == Verdict::Localized && (same || !odometry_holds);
  const bool surprise = takes && hypothesis.confirmed && surprising(hypothesis, e.pose);
  if ((surprise || !odometry_holds) && look_alikes != nullptr &&
      splits_off(hypothesis, near.pose, e.pose)) {
    // The winner joins as a place of its own, weighted by the odometry's prior; this one
    // stays where the odometry put it, at its best heading within the odometry's doubt, with
    // the scan's evidence there.
    look_alikes->push_back(
        {e.pose, log_prior(e.pose, prior.carried, prior.covariance, prior.floor)});
    const double half_theta = kept_half_theta(hypothesis);
    e = half_theta > 2.0 * global.step_theta
            ? best_near(hypothesis.pose, observation, global, half_theta)
            : near;  // the same window as near's
    hypothesis.pose = e.pose;
    e.verdict = Verdict::NotLocalized;
    hypothesis.held_back = HeldBack::SplitOff;
    return;
  }
  if (takes) {
    hypothesis.held_back = moved_held_back(hypothesis, e, surprise, weak);
    if (hypothesis.held_back != HeldBack::None) e.verdict = Verdict::NotLocalized;
    take_winner(hypothesis, e);
    return;
  }
  if (!odometry_holds) {  // look-alikes in the window, and the odometry's place is not one
    hypothesis.pose = e.pose;
    e.verdict = Verdict::NotLocalized;
    hypothesis.held_back = HeldBack::LookAlikes;
    return;
  }
  keep_odometry_place(hypothesis, e, near, fits_as_usual, weak);
}

void Localizer::take_winner(TrackedHypothesis& hypothesis, const Estimate& e) const {
  const bool fuses = options_.fuse_carried_position && laser_ && hypothesis.confirmed &&
                     hypothesis.held_back == HeldBack::None;
  if (!fuses) {
    hypothesis.pose = e.pose;
    hypothesis.covariance = e.covariance;
  } else {
    // The window's winner and where the odometry carried the place, two estimates of one
    // position: the Kalman update weighs them by their covariances (the window's widened by
    // the map's error it does not see). The heading is the window's.
    const Eigen::Matrix2d carried = hypothesis.covariance.topLeftCorner<2, 2>();
    const double unseen = options_.fused_window_error_m * options_.fused_window_error_m;
    const Eigen::Matrix2d window =
        e.covariance.topLeftCorner<2, 2>() + unseen * Eigen::Matrix2d::Identity();
    const Eigen::Matrix2d gain =
        carried * (carried + window + 1e-15 * Eigen::Matrix2d::Identity()).inverse();
    const Eigen::Vector2d position =
        Eigen::Vector2d(hypothesis.pose.x, hypothesis.pose.y) +
        gain * Eigen::Vector2d(e.pose.x - hypothesis.pose.x, e.pose.y - hypothesis.pose.y);
    hypothesis.pose = Pose2{position.x(), position.y(), e.pose.theta};
    hypothesis.covariance = Eigen::Matrix3d::Zero();
    hypothesis.covariance.topLeftCorner<2, 2>() = carried - gain * carried;
    hypothesis.covariance(2, 2) = e.covariance(2, 2);
  }
  hypothesis.confirmed = true;
}

HeldBack Localizer::moved_held_back(const TrackedHypothesis& carried, const Estimate& e,
                                    bool surprise, bool weak) const {
  // A step the odometry did not make is not trusted yet (the place follows it: a slip holds
  // at the next observation, a wrong match does not). A scan's window whose own spread is
  // wider than a localized place's is not one (the place the odometry holds is asked the
  // same of its fused covariance).
  return surprise                                    ? HeldBack::Surprise
         : weak                                      ? HeldBack::WeakFit
         : laser_ && !tight(e.covariance)            ? HeldBack::WideWindow
         : laser_ && turns_on_a_weak_fit(carried, e) ? HeldBack::TurnOnWeakFit
                                                     : HeldBack::None;
}

void Localizer::keep_odometry_place(TrackedHypothesis& hypothesis, Estimate& e,
                                    const Estimate& near, bool fits_as_usual, bool weak) const {
  // The scan fits the odometry's place as well as any: the place stays there, the window's
  // spread widened by the gap between its winner and that place narrows the grown covariance
  // (along a corridor the gap keeps it wide), and the place stays `localized` while tight.
  hypothesis.pose = near.pose;
  if (fits_as_usual) {
    const Eigen::Vector3d gap(near.pose.x - e.pose.x, near.pose.y - e.pose.y,
                              normalize_angle(near.pose.theta - e.pose.theta));
    hypothesis.covariance = fused(hypothesis.covariance, e.covariance + gap * gap.transpose());
  }
  hypothesis.held_back = !tight(hypothesis.covariance) ? HeldBack::WideCarried
                         : !hypothesis.confirmed       ? HeldBack::Unconfirmed
                         : weak                        ? HeldBack::WeakFit
                                                       : HeldBack::None;
  e.verdict = hypothesis.held_back == HeldBack::None ? Verdict::Localized : Verdict::NotLocalized;
}

bool Localizer::place_on_weak_fit(TrackedHypothesis& hypothesis, Estimate& e,
                                  bool after_a_miss) const {
  const bool placed = hypothesis.confirmed &&
                      e.normalized_score >= options_.weak_fit_ratio * hypothesis.usual_fit &&
                      tight(e.covariance) && !surprising(hypothesis, e.pose);
  if (!placed) return false;
  hypothesis.pose = e.pose;
  hypothesis.covariance = fused(hypothesis.covariance, e.covariance);
  const bool weak = e.normalized_score < options_.localized_fit_ratio * hypothesis.usual_fit;
  hypothesis.held_back = !tight(hypothesis.covariance) ? HeldBack::WideCarried
                         : weak || after_a_miss        ? HeldBack::WeakFit
                                                       : HeldBack::None;
  e.verdict = hypothesis.held_back == HeldBack::None ? Verdict::Localized : Verdict::NotLocalized;
  return true;
}

bool Localizer::turns_on_a_weak_fit(const TrackedHypothesis& carried, const Estimate& e) const {
  const bool turned =
      std::abs(normalize_angle(e.pose.theta - carried.pose.theta)) > options_.step_min_rad;
  return turned && e.normalized_score < options_.turn_fit_ratio * carried.usual_fit;
}

bool Localizer::splits_off(const TrackedHypothesis& hypothesis, const Pose2& kept,
                           const Pose2& winner) const {
  const HypothesisSetOptions& set = options_.hypothesis_set;
  const bool apart = std::hypot(winner.x - kept.x, winner.y - kept.y) > set.merge_xy ||
                     std::abs(normalize_angle(winner.theta - kept.theta)) > set.merge_theta;
  return options_.split_far_winners && laser_ && hypothesis.confirmed && apart;
}

double Localizer::kept_half_theta(const TrackedHypothesis& carried) const {
  return std::min(options_.kept_max_half_theta,
                  options_.kept_heading_sigmas * std::sqrt(carried.covariance(2, 2)));
}

bool Localizer::tight(const Eigen::Matrix3d& covariance) const {
  const double sigma_m = laser_ ? options_.laser_localized_sigma_m : options_.localized_sigma_m;
  return std::sqrt(std::max(covariance(0, 0), covariance(1, 1))) <= sigma_m &&
         std::sqrt(covariance(2, 2)) <= options_.localized_sigma_rad;
}

bool Localizer::surprising(const TrackedHypothesis& predicted, const Pose2& placed) const {
  const Eigen::Matrix3d& c = predicted.covariance;
  const double sigma_xy = std::sqrt(std::max(c(0, 0), c(1, 1)));
  const double allowed_xy = std::max(options_.step_min_m, options_.prior_sigmas * sigma_xy);
  const double allowed_theta =
      std::max(options_.step_min_rad, options_.prior_sigmas * std::sqrt(c(2, 2)));
  return std::hypot(placed.x - predicted.pose.x, placed.y - predicted.pose.y) > allowed_xy ||
         std::abs(normalize_angle(placed.theta - predicted.pose.theta)) > allowed_theta;
}

}  // namespace gridloc
