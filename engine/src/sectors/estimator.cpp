// Seed 000's visibility sectors behind the Estimator interface, alone and refined by the
// correlation search.
#include "gridloc/engine/sectors/estimator.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SectorEstimator::SectorEstimator(const PolygonMap& map, SectorEstimatorOptions options)
    : sectors_(compute_sectors(map, options.sectors)), options_(options) {
  if (!(options_.residual_scale_m > 0.0) || !std::isfinite(options_.residual_scale_m)) {
    throw Error("SectorEstimatorOptions.residual_scale_m must be positive, got " +
                std::to_string(options_.residual_scale_m));
  }
}

SectorFix SectorEstimator::fix(const Observation& observation) const {
  if (!observation.scan) {
    throw Error(
        "sectors estimator: needs a 360 degree laser scan (--scan); a sonar ring's 14 echoes "
        "give no label");
  }
  return localize_in_sectors(sectors_, *observation.scan, options_.localization);
}

Estimate SectorEstimator::to_estimate(const SectorFix& f, const SearchWindow& window,
                                      double elapsed_ms) const {
  Estimate e;
  e.pose = e.lattice_pose = f.found ? f.pose : window.center;
  e.confidence = f.found ? std::exp(-f.residual_m / options_.residual_scale_m) : 0.0;
  e.score = e.normalized_score = e.confidence;
  e.second_score = std::numeric_limits<double>::quiet_NaN();
  e.confidence_parts.fit = e.confidence;
  e.confidence_parts.agreement = 1.0;
  e.confidence_parts.distinctness = f.ambiguous ? 0.0 : 1.0;
  e.confidence_parts.sharpness = 1.0;
  e.agreement = std::numeric_limits<double>::quiet_NaN();
  e.ambiguous = f.ambiguous;
  e.verdict = !f.found || e.confidence < options_.localized_confidence ? Verdict::NotLocalized
              : f.ambiguous                                            ? Verdict::Ambiguous
                                                                       : Verdict::Localized;
  e.on_window_edge = f.found && (std::abs(f.pose.x - window.center.x) > window.half_xy ||
                                 std::abs(f.pose.y - window.center.y) > window.half_xy);
  // The look-alikes of an ambiguous fix, best first, scored like the confidence.
  for (const SectorFix::Alternative& a : f.alternatives) {
    e.alternatives.push_back({a.pose, std::exp(-a.residual_m / options_.residual_scale_m)});
  }
  if (e.alternatives.empty()) e.alternatives = {{e.pose, e.score}};
  if (e.alternatives.size() > 1) e.second_score = e.alternatives[1].score;
  e.covariance = f.covariance;
  e.stats.poses_scored = f.candidates;
  e.stats.proven_optimal = false;
  e.stats.upper_bound = std::numeric_limits<double>::quiet_NaN();
  e.stats.elapsed_ms = elapsed_ms;
  return e;
}

SectorEstimate SectorEstimator::locate(const Observation& observation,
                                       const SearchWindow& window) const {
  validate(window);
  const auto t0 = std::chrono::steady_clock::now();
  SectorFix f = fix(observation);
  Estimate e = to_estimate(f, window, ms_since(t0));
  return {std::move(e), std::move(f)};
}

Estimate SectorEstimator::estimate(const Observation& observation,
                                   const SearchWindow& window) const {
  return locate(observation, window).estimate;
}

SectorCorrelationEstimator::SectorCorrelationEstimator(
    std::shared_ptr<const SectorEstimator> sectors,
    std::shared_ptr<const CorrelationEstimator> correlation, SectorCorrelationOptions options)
    : sectors_(std::move(sectors)), correlation_(std::move(correlation)), options_(options) {
  if (!sectors_ || !correlation_) {
    throw Error("SectorCorrelationEstimator: needs a sector and a correlation estimator");
  }
  if (!(options_.half_xy > 0.0) || !(options_.half_theta > 0.0) ||
      !std::isfinite(options_.half_xy) || !std::isfinite(options_.half_theta)) {
    throw Error("SectorCorrelationOptions: half_xy and half_theta must be positive, got " +
                std::to_string(options_.half_xy) + " and " + std::to_string(options_.half_theta));
  }
}

Estimate SectorCorrelationEstimator::estimate(const Observation& observation,
                                              const SearchWindow& window) const {
  return locate(observation, window).estimate;
}

SectorEstimate SectorCorrelationEstimator::locate(const Observation& observation,
                                                  const SearchWindow& window) const {
  validate(window);
  const auto t0 = std::chrono::steady_clock::now();
  SectorFix f = sectors_->fix(observation);
  Estimate e = sectors_->to_estimate(f, window, 0.0);
  if (f.found) {
    SearchWindow local = correlation_->global_window(observation);  // its heading step
    local.center = f.pose;
    local.half_xy = options_.half_xy;
    local.half_theta = options_.half_theta;
    const Estimate c = correlation_->estimate(observation, local);
    e.pose = c.pose;
    e.lattice_pose = c.lattice_pose;
    e.score = c.score;
    e.normalized_score = c.normalized_score;
    e.covariance = c.covariance;
    e.alternatives.front() = {e.pose, e.score};  // the look-alikes stay the fix's
    e.stats.cells_scored = c.stats.cells_scored;
    e.stats.poses_scored += c.stats.poses_scored;
    e.on_window_edge = std::abs(e.pose.x - window.center.x) > window.half_xy ||
                       std::abs(e.pose.y - window.center.y) > window.half_xy;
  }
  e.stats.elapsed_ms = ms_since(t0);
  return {std::move(e), std::move(f)};
}

}  // namespace gridloc
