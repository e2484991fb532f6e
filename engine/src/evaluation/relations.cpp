#include "gridloc/engine/evaluation/relations.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/breakpoints.hpp"
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

/// The farthest of `points` from the origin (m).
double farthest(const std::vector<Eigen::Vector2d>& points) {
  double far = 0.0;
  for (const auto& p : points) far = std::max(far, p.norm());
  return far;
}

/// Estimated bytes of the search grids of a `map` padded by `pad` cells: the padded grid and
/// its arc view (float each, plus int8 copies), the bound pyramid's levels of both (the
/// same again per level) for branch and bound, and the global grid's construction.
double search_bytes(const GridGeometry& map, int pad, SearchStrategy strategy) {
  const double padded = (map.width + 2.0 * pad) * (map.height + 2.0 * pad);
  int depth = 0;
  if (strategy == SearchStrategy::BranchAndBound) {
    while ((1 << depth) < std::max(map.width, map.height)) ++depth;
    ++depth;  // as the estimator sizes it
  }
  constexpr double per_level = 2 * sizeof(float) + 2 * sizeof(std::int8_t);
  constexpr double per_map_cell = 4 * sizeof(float);
  return padded * per_level * (1.0 + depth) +
         per_map_cell * static_cast<double>(map.width) * static_cast<double>(map.height);
}

/// Throws gridloc::Error when the search of a `map` padded by `pad` cells would take more
/// than options.max_search_mb.
void check_search_size(const GridGeometry& map, int pad, const RelationEvalOptions& options) {
  const double mb = search_bytes(map, pad, options.correlation.strategy) / (1024.0 * 1024.0);
  if (mb <= options.max_search_mb) return;
  std::ostringstream m;
  m << "relations: the search grids would take about " << std::lround(mb) << " MB (a " << map.width
    << " x " << map.height << " cell map padded by " << pad << " cells of " << map.resolution
    << " m), more than max_search_mb = " << options.max_search_mb;
  throw Error(m.str());
}

/// The correlation search's estimate of the motion of `current` (whose returns are
/// `current_points`) on the map of `reference`, in a window around `prior`; `cells` gets
/// the padded search grid's size.
Estimate correlate(const RangeScan& reference, const RangeScan& current,
                   const std::vector<Eigen::Vector2d>& current_points, const Pose2& prior,
                   const RelationEvalOptions& options, std::size_t& cells) {
  // The reference scan as a map whose world frame is the reference robot's frame.
  // Its margin keeps the whole search window on the map.
  const double half_xy = options.prior_noise_xy + options.window_margin_xy;
  ScanMapOptions drawing;
  drawing.resolution = options.map_resolution;
  drawing.margin_m = 0.5 + std::hypot(prior.x, prior.y) + 1.5 * half_xy;
  drawing.join_returns = options.join_returns;
  drawing.join_gap_m = options.join_gap_m;
  drawing.join_grazing_rad = options.join_grazing_rad;
  OccupancyMap map = scan_occupancy_map(reference, drawing);
  // The current scan's max range cut to its farthest return: the padding then covers what
  // the scan reaches, not the logger's 80 m "no return".
  RangeScan cut = current;
  cut.max_range = std::min(cut.max_range, farthest(current_points) + options.map_resolution);
  CorrelationOptions correlation = options.correlation;
  correlation.resolution = options.map_resolution;
  correlation.reach_m = cut.max_range;
  // The estimator's padding (correlation estimator: reach in cells plus 3).
  const int pad = static_cast<int>(std::ceil(correlation.reach_m / correlation.resolution)) + 3;
  check_search_size(map.geometry, pad, options);
  cells = static_cast<std::size_t>(map.geometry.width + 2 * pad) *
          static_cast<std::size_t>(map.geometry.height + 2 * pad);
  const CorrelationEstimator estimator(std::move(map), correlation);
  Observation observation;
  observation.scan = cut;
  SearchWindow window = estimator.global_window(observation);  // for its heading step
  window.center = prior;
  window.half_xy = half_xy;
  window.half_theta = options.prior_noise_theta + options.window_margin_theta;
  window.step_xy = options.map_resolution;
  return estimator.estimate(observation, window);
}

/// ICP's pose from the search's `coarse` one when it converged within the refinement limits.
std::optional<IcpResult> refine_by_icp(const std::vector<Eigen::Vector2d>& reference_points,
                                       const std::vector<Eigen::Vector2d>& current_points,
                                       const Pose2& coarse, const RelationEvalOptions& options) {
  const IcpResult refined = icp_or_none(reference_points, current_points, coarse, options.icp);
  const bool near =
      std::hypot(refined.pose.x - coarse.x, refined.pose.y - coarse.y) <=
          options.refine_max_shift_m &&
      std::abs(normalize_angle(refined.pose.theta - coarse.theta)) <= options.refine_max_turn_rad;
  if (refined.converged && near) return refined;
  return std::nullopt;
}

/// Prefixes a pair's error with the pair it happened on.
Error in_pair(const Error& e, std::size_t index, const RelationPair& pair) {
  std::string what = e.what();
  const std::string prefix = "relations: ";
  if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
  std::ostringstream m;
  m << std::fixed << std::setprecision(3) << "relations: pair " << index << " (t1 "
    << pair.relation.t1 << " s, t2 " << pair.relation.t2 << " s): " << what;
  return Error(m.str());
}

}  // namespace

CorrelationOptions exhaustive_search() {
  CorrelationOptions options;
  options.strategy = SearchStrategy::Exhaustive;
  options.covariance_cells = 5;
  options.covariance_temperature = 10.0;
  options.covariance_spans_peaks = true;
  return options;
}

void validate(const RelationEvalOptions& o) {
  auto at_least = [](double value, double low, bool strict, const char* name) {
    const bool ok = std::isfinite(value) && (strict ? value > low : value >= low);
    if (!ok) {
      std::ostringstream m;
      m << "relations options: " << name << " must be " << (strict ? "> " : ">= ") << low
        << ", got " << value;
      throw Error(m.str());
    }
  };
  at_least(o.prior_noise_xy, 0.0, false, "prior_noise_xy");
  at_least(o.prior_noise_theta, 0.0, false, "prior_noise_theta");
  at_least(o.failure_xy, 0.0, true, "failure_xy");
  at_least(o.failure_theta, 0.0, true, "failure_theta");
  at_least(o.map_resolution, 0.0, true, "map_resolution");
  at_least(o.window_margin_xy, 0.0, false, "window_margin_xy");
  at_least(o.join_gap_m, 0.0, false, "join_gap_m");
  check_grazing_angle(o.join_grazing_rad, "relations options: join_grazing_rad");
  at_least(o.window_margin_theta, 0.0, false, "window_margin_theta");
  at_least(o.refine_max_shift_m, 0.0, false, "refine_max_shift_m");
  at_least(o.refine_max_turn_rad, 0.0, false, "refine_max_turn_rad");
  at_least(o.max_search_mb, 0.0, true, "max_search_mb");
  at_least(o.overlap_radius_m, 0.0, true, "overlap_radius_m");
  at_least(o.overlapping_share, 0.0, false, "overlapping_share");
  if (o.overlapping_share > 1.0) {
    throw Error("relations options: overlapping_share must be <= 1, got " +
                std::to_string(o.overlapping_share));
  }
  check_band_edges(o.overlap_band_edges);
}

PairMatch match_relation_pair(const RangeScan& reference, const RangeScan& current,
                              const Pose2& prior, const RelationEvalOptions& options) {
  if (is_sector_estimator(options.matcher)) {
    throw Error("relations: the " + to_string(options.matcher) +
                " estimator localizes on a polygon map, it does not match two scans; use icp, "
                "correlation or correlation+icp");
  }
  validate(options);
  const auto reference_points = scan_returns(reference);
  const auto current_points = scan_returns(current);
  PairMatch match;
  // ICP on scans it cannot use fails to match, like a match that does not converge; it does
  // not end the evaluation.
  if (options.matcher == EstimatorKind::Icp) {
    const IcpResult icp = icp_or_none(reference_points, current_points, prior, options.icp);
    match.pose = icp.pose;
    match.converged = icp.converged;
    match.covariance = icp.covariance;
    return match;
  }
  const Estimate coarse =
      correlate(reference, current, current_points, prior, options, match.search_cells);
  match.pose = coarse.pose;
  match.verdict = coarse.verdict;
  match.confidence = coarse.confidence;
  match.covariance = coarse.covariance;
  if (options.matcher == EstimatorKind::CorrelationIcp) {
    const auto refined = refine_by_icp(reference_points, current_points, coarse.pose, options);
    match.refined = refined.has_value();
    if (refined) match.pose = refined->pose;
    if (options.icp_from_prior) {
      // ICP from the prior too: its answer wins when it fits more pairs.
      const IcpResult alt = icp_or_none(reference_points, current_points, prior, options.icp);
      const std::size_t fitting = refined ? refined->fitting_pairs : 0;
      if (alt.converged && alt.fitting_pairs > fitting) match.pose = alt.pose;
    }
  }
  return match;
}

Pose2 match_pair(const RangeScan& reference, const RangeScan& current, const Pose2& prior,
                 const RelationEvalOptions& options, bool* converged) {
  const PairMatch match = match_relation_pair(reference, current, prior, options);
  if (converged != nullptr) *converged = match.converged;
  return match.pose;
}

namespace {

/// The prior of `pair`: the logged motion plus the next draws of `rng`.
Pose2 noisy_prior(const CarmenLog& log, const RelationPair& pair,
                  const RelationEvalOptions& options, Rng& rng) {
  Pose2 prior =
      relative_pose(log.lasers[pair.first].laser_pose, log.lasers[pair.second].laser_pose);
  prior.x += rng.uniform(-options.prior_noise_xy, options.prior_noise_xy);
  prior.y += rng.uniform(-options.prior_noise_xy, options.prior_noise_xy);
  prior.theta = normalize_angle(prior.theta +
                                rng.uniform(-options.prior_noise_theta, options.prior_noise_theta));
  return prior;
}

/// Matches pair `index` of `pairs` from `prior` and scores it against its relation.
RelationTrial run_trial(const CarmenLog& log, const RelationPair& pair, std::size_t index,
                        const Pose2& prior, const RelationEvalOptions& options) {
  const LaserRecord& first = log.lasers[pair.first];
  const LaserRecord& second = log.lasers[pair.second];
  const auto t0 = std::chrono::steady_clock::now();
  PairMatch match;
  try {
    match = match_relation_pair(first.scan, second.scan, prior, options);
  } catch (const Error& e) {
    throw in_pair(e, index, pair);
  }
  RelationTrial trial;
  trial.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  trial.pair = index;
  trial.t1 = pair.relation.t1;
  trial.t2 = pair.relation.t2;
  trial.motion_m = std::hypot(pair.relation.motion.x, pair.relation.motion.y);
  trial.motion_deg = rad2deg(std::abs(normalize_angle(pair.relation.motion.theta)));
  const auto current_points = scan_returns(second.scan);
  trial.returns = static_cast<int>(current_points.size());
  const auto reference_points = scan_returns(first.scan);
  trial.overlap = scan_overlap(reference_points, current_points, pair.relation.motion,
                               options.overlap_radius_m);
  trial.answer_overlap =
      scan_overlap(reference_points, current_points, match.pose, options.overlap_radius_m);
  // The benchmark's error: the estimate seen from the true motion.
  const Pose2 error = relative_pose(pair.relation.motion, match.pose);
  trial.translation_error_m = std::hypot(error.x, error.y);
  trial.rotation_error_deg = rad2deg(std::abs(error.theta));
  trial.converged = match.converged;
  trial.failed = !match.converged || trial.translation_error_m > options.failure_xy ||
                 std::abs(error.theta) > options.failure_theta;
  trial.verdict = match.verdict;
  trial.confidence = match.confidence;
  trial.refined = match.refined;
  trial.search_cells = match.search_cells;
  trial.truth = pair.relation.motion;
  trial.answer = match.pose;
  trial.covariance = match.covariance;
  trial.within_2sigma = within_2sigma_ellipse(match.pose, match.covariance, pair.relation.motion);
  return trial;
}

/// The verdict's row label: "none" for a matcher without one (ICP alone).
std::string verdict_label(const std::optional<Verdict>& verdict) {
  return verdict ? to_string(*verdict) : "none";
}

/// The failure tables of `report`'s trials: by overlap band, by verdict and overlapping.
void tabulate_failures(RelationEvalReport& report, const RelationEvalOptions& options) {
  std::vector<double> overlaps;
  std::vector<bool> failed;
  char overlapping[48];
  std::snprintf(overlapping, sizeof overlapping, "overlap >= %g", options.overlapping_share);
  report.overlapping.label = overlapping;
  for (const RelationTrial& t : report.trials) {
    overlaps.push_back(t.overlap);
    failed.push_back(t.failed);
    if (t.overlap < options.overlapping_share) continue;
    ++report.overlapping.pairs;
    if (t.failed) ++report.overlapping.failures;
  }
  report.failures_by_overlap = failures_by_band(overlaps, failed, options.overlap_band_edges);
  for (const char* label : {"localized", "ambiguous", "not localized", "none"}) {
    FailureRow row{label, 0, 0};
    for (const RelationTrial& t : report.trials) {
      if (verdict_label(t.verdict) != label) continue;
      ++row.pairs;
      if (t.failed) ++row.failures;
    }
    if (row.pairs > 0) report.failures_by_verdict.push_back(row);
  }
  std::vector<CalibrationSample> samples;
  for (const RelationTrial& t : report.trials) {
    const bool used = t.verdict ? *t.verdict == Verdict::Localized : t.converged;
    samples.push_back({t.answer, t.covariance, t.truth, used});
    if (used && t.failed && t.within_2sigma) ++report.covered_failures;
  }
  report.calibration = summarize_calibration(samples);
}

/// The report's totals from its trials.
void summarize(RelationEvalReport& report, const RelationEvalOptions& options) {
  std::vector<double> translation_errors, rotation_errors, ms;
  for (const RelationTrial& t : report.trials) {
    translation_errors.push_back(t.translation_error_m);
    rotation_errors.push_back(t.rotation_error_deg);
    ms.push_back(t.ms);
    if (!t.converged) ++report.not_converged;
    if (t.failed) ++report.failures;
  }
  report.pairs = static_cast<int>(report.trials.size());
  report.translation_error_m = error_stats(translation_errors);
  report.rotation_error_deg = error_stats(rotation_errors);
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  report.median_ms = ms[ms.size() / 2];
  tabulate_failures(report, options);
}

}  // namespace

RelationEvalReport evaluate_relations(const CarmenLog& log, const std::vector<RelationPair>& pairs,
                                      const RelationEvalOptions& options) {
  if (pairs.empty()) throw Error("relations: no relation falls on two scans of the log");
  validate(options);
  Rng rng(options.seed);
  RelationEvalReport report;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const RelationPair& pair = pairs[k];
    if (pair.first >= log.lasers.size() || pair.second >= log.lasers.size()) {
      throw Error("relations: a pair names scan " +
                  std::to_string(std::max(pair.first, pair.second)) + " of a log of " +
                  std::to_string(log.lasers.size()));
    }
    const Pose2 prior = noisy_prior(log, pair, options, rng);
    report.trials.push_back(run_trial(log, pair, k, prior, options));
  }
  summarize(report, options);
  return report;
}

}  // namespace gridloc
