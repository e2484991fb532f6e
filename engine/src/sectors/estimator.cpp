// Seed 000's visibility sectors behind the Estimator interface, alone and refined by the
// correlation search.
#include "gridloc/engine/sectors/estimator.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SectorEstimator::SectorEstimator(const PolygonMap& map, SectorEstimatorOptions options)
    : SectorEstimator(compute_sectors(map, options.sectors), options) {}

SectorEstimator::SectorEstimator(SectorMap sectors, SectorEstimatorOptions options)
    : sectors_(std::move(sectors)), options_(options) {
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

Estimate SectorEstimator::to_estimate(const SectorFix& sector_fix, const SearchWindow& window,
                                      double elapsed_ms) const {
  Estimate result;
  result.pose = result.lattice_pose = sector_fix.found ? sector_fix.pose : window.center;
  result.confidence =
      sector_fix.found ? std::exp(-sector_fix.residual_m / options_.residual_scale_m) : 0.0;
  result.score = result.normalized_score = result.confidence;
  result.second_score = std::numeric_limits<double>::quiet_NaN();
  result.confidence_parts.fit = result.confidence;
  result.confidence_parts.agreement = 1.0;
  result.confidence_parts.distinctness = sector_fix.ambiguous ? 0.0 : 1.0;
  result.confidence_parts.sharpness = 1.0;
  result.agreement = std::numeric_limits<double>::quiet_NaN();
  result.ambiguous = sector_fix.ambiguous;
  result.verdict = !sector_fix.found || result.confidence < options_.localized_confidence
                       ? Verdict::NotLocalized
                   : sector_fix.ambiguous ? Verdict::Ambiguous
                                          : Verdict::Localized;
  result.on_window_edge =
      sector_fix.found && (std::abs(sector_fix.pose.x - window.center.x) > window.half_xy ||
                           std::abs(sector_fix.pose.y - window.center.y) > window.half_xy);
  // The look-alikes of an ambiguous fix, best first, scored like the confidence.
  for (const SectorFix::Alternative& a : sector_fix.alternatives) {
    result.alternatives.push_back({a.pose, std::exp(-a.residual_m / options_.residual_scale_m)});
  }
  if (result.alternatives.empty()) result.alternatives = {{result.pose, result.score}};
  if (result.alternatives.size() > 1) result.second_score = result.alternatives[1].score;
  result.covariance = sector_fix.covariance;
  result.stats.poses_scored = sector_fix.candidates;
  result.stats.proven_optimal = false;
  result.stats.upper_bound = std::numeric_limits<double>::quiet_NaN();
  result.stats.elapsed_ms = elapsed_ms;
  return result;
}

SectorEstimate SectorEstimator::locate(const Observation& observation,
                                       const SearchWindow& window) const {
  validate(window);
  const auto t0 = std::chrono::steady_clock::now();
  SectorFix sector_fix = fix(observation);
  Estimate result = to_estimate(sector_fix, window, ms_since(t0));
  return {std::move(result), std::move(sector_fix)};
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
  SectorFix sector_fix = sectors_->fix(observation);
  Estimate result = sectors_->to_estimate(sector_fix, window, 0.0);
  if (sector_fix.found) {
    SearchWindow local = correlation_->global_window(observation);  // its heading step
    local.center = sector_fix.pose;
    local.half_xy = options_.half_xy;
    local.half_theta = options_.half_theta;
    const Estimate refined = correlation_->estimate(observation, local);
    result.pose = refined.pose;
    result.lattice_pose = refined.lattice_pose;
    result.score = refined.score;
    result.normalized_score = refined.normalized_score;
    result.covariance = refined.covariance;
    result.alternatives.front() = {result.pose, result.score};  // the look-alikes stay the fix's
    result.stats.cells_scored = refined.stats.cells_scored;
    result.stats.poses_scored += refined.stats.poses_scored;
    result.on_window_edge = std::abs(result.pose.x - window.center.x) > window.half_xy ||
                            std::abs(result.pose.y - window.center.y) > window.half_xy;
  }
  result.stats.elapsed_ms = ms_since(t0);
  return {std::move(result), std::move(sector_fix)};
}

}  // namespace gridloc
