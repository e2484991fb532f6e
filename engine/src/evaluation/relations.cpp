#include "gridloc/engine/evaluation/relations.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_map.hpp"

namespace gridloc {
namespace {

ErrorStats error_stats(const std::vector<double>& v) {
  ErrorStats stats;
  if (v.empty()) return stats;
  for (double x : v) stats.mean += x / static_cast<double>(v.size());
  double variance = 0.0;
  for (double x : v)
    variance += (x - stats.mean) * (x - stats.mean) / static_cast<double>(v.size());
  stats.std = std::sqrt(variance);
  return stats;
}

/// ICP of `current` on `reference` from `start`; a scan ICP cannot use (too few returns in
/// segments) gives a result that did not converge, at `start`.
IcpResult icp_or_none(const std::vector<Eigen::Vector2d>& reference,
                      const std::vector<Eigen::Vector2d>& current, const Pose2& start,
                      const IcpOptions& options) {
  try {
    return match_scans(reference, current, start, options);
  } catch (const Error&) {
    IcpResult none;
    none.pose = start;
    return none;
  }
}

/// The correlation search's motion of `current` (whose returns are `current_points`) on
/// the map of `reference`, in a window around `prior`.
Pose2 correlate(const RangeScan& reference, const RangeScan& current,
                const std::vector<Eigen::Vector2d>& current_points, const Pose2& prior,
                const RelationEvalOptions& options) {
  // The reference scan as a map whose world frame is the reference robot's frame.
  // Its margin keeps the whole search window on the map.
  const double half_xy = options.prior_noise_xy + options.window_margin_xy;
  OccupancyMap map = scan_occupancy_map(reference, options.map_resolution,
                                        0.5 + std::hypot(prior.x, prior.y) + 1.5 * half_xy);
  // The current scan's max range cut to its farthest return: the padding then covers what
  // the scan reaches, not the logger's 80 m "no return".
  RangeScan cut = current;
  double farthest = 0.0;
  for (const auto& p : current_points) farthest = std::max(farthest, p.norm());
  cut.max_range = std::min(cut.max_range, farthest + options.map_resolution);
  CorrelationOptions correlation = options.correlation;
  correlation.resolution = options.map_resolution;
  correlation.reach_m = cut.max_range;
  const CorrelationEstimator estimator(std::move(map), correlation);
  Observation observation;
  observation.scan = cut;
  SearchWindow window = estimator.global_window(observation);  // for its heading step
  window.center = prior;
  window.half_xy = half_xy;
  window.half_theta = options.prior_noise_theta + options.window_margin_theta;
  window.step_xy = options.map_resolution;
  return estimator.estimate(observation, window).pose;
}

}  // namespace

Pose2 match_pair(const RangeScan& reference, const RangeScan& current, const Pose2& prior,
                 const RelationEvalOptions& options, bool* converged) {
  if (is_sector_estimator(options.matcher)) {
    throw Error("relations: the " + to_string(options.matcher) +
                " estimator localizes on a polygon map, it does not match two scans; use icp, "
                "correlation or correlation+icp");
  }
  if (converged != nullptr) *converged = true;
  const auto reference_points = scan_returns(reference);
  const auto current_points = scan_returns(current);
  // ICP on scans it cannot use fails to match, like a match that does not converge; it does
  // not end the evaluation.
  if (options.matcher == EstimatorKind::Icp) {
    const IcpResult match = icp_or_none(reference_points, current_points, prior, options.icp);
    if (converged != nullptr) *converged = match.converged;
    return match.pose;
  }
  const Pose2 coarse = correlate(reference, current, current_points, prior, options);
  if (options.matcher == EstimatorKind::Correlation) return coarse;
  const IcpResult refined = icp_or_none(reference_points, current_points, coarse, options.icp);
  if (refined.converged &&
      std::hypot(refined.pose.x - coarse.x, refined.pose.y - coarse.y) <=
          options.refine_max_shift_m &&
      std::abs(normalize_angle(refined.pose.theta - coarse.theta)) <= options.refine_max_turn_rad) {
    return refined.pose;
  }
  return coarse;
}

RelationEvalReport evaluate_relations(const CarmenLog& log, const std::vector<RelationPair>& pairs,
                                      const RelationEvalOptions& options) {
  if (pairs.empty()) throw Error("relations: no relation falls on two scans of the log");
  Rng rng(options.seed);
  std::vector<double> translation_errors, rotation_errors, ms;
  RelationEvalReport report;
  for (const RelationPair& pair : pairs) {
    if (pair.first >= log.lasers.size() || pair.second >= log.lasers.size()) {
      throw Error("relations: a pair names scan " +
                  std::to_string(std::max(pair.first, pair.second)) + " of a log of " +
                  std::to_string(log.lasers.size()));
    }
    const LaserRecord& first = log.lasers[pair.first];
    const LaserRecord& second = log.lasers[pair.second];
    Pose2 prior = relative_pose(first.laser_pose, second.laser_pose);
    prior.x += rng.uniform(-options.prior_noise_xy, options.prior_noise_xy);
    prior.y += rng.uniform(-options.prior_noise_xy, options.prior_noise_xy);
    prior.theta = normalize_angle(
        prior.theta + rng.uniform(-options.prior_noise_theta, options.prior_noise_theta));
    const auto t0 = std::chrono::steady_clock::now();
    bool converged = true;
    const Pose2 estimate = match_pair(first.scan, second.scan, prior, options, &converged);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    // The benchmark's error: the estimate seen from the true motion.
    const Pose2 error = relative_pose(pair.relation.motion, estimate);
    const double translation = std::hypot(error.x, error.y), rotation = std::abs(error.theta);
    translation_errors.push_back(translation);
    rotation_errors.push_back(rad2deg(rotation));
    if (!converged) ++report.not_converged;
    if (!converged || translation > options.failure_xy || rotation > options.failure_theta) {
      ++report.failures;
    }
  }
  report.pairs = static_cast<int>(pairs.size());
  report.translation_error_m = error_stats(translation_errors);
  report.rotation_error_deg = error_stats(rotation_errors);
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  report.median_ms = ms[ms.size() / 2];
  return report;
}

}  // namespace gridloc
