#include "gridloc/engine/evaluation/relations.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_map.hpp"

namespace gridloc {
namespace {

ErrorStats stats(const std::vector<double>& v) {
  ErrorStats s;
  if (v.empty()) return s;
  for (double x : v) s.mean += x / static_cast<double>(v.size());
  double var = 0.0;
  for (double x : v) var += (x - s.mean) * (x - s.mean) / static_cast<double>(v.size());
  s.std = std::sqrt(var);
  return s;
}

}  // namespace

Pose2 relative_pose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, normalize_angle(b.theta - a.theta)};
}

Pose2 match_pair(const RangeScan& reference, const RangeScan& current, const Pose2& prior,
                 const RelationEvalOptions& o, bool* converged) {
  if (is_sector_estimator(o.matcher)) {
    throw Error("relations: the " + to_string(o.matcher) +
                " estimator localizes on a polygon map, it does not match two scans; use icp, "
                "correlation or correlation+icp");
  }
  if (converged != nullptr) *converged = true;
  const auto ref_points = scan_returns(reference);
  const auto cur_points = scan_returns(current);
  // ICP on scans it cannot use (too few returns in segments) fails to match, like a match
  // that does not converge; it does not end the evaluation.
  const auto icp = [&](const Pose2& start) {
    try {
      return match_scans(ref_points, cur_points, start, o.icp);
    } catch (const Error&) {
      IcpResult none;
      none.pose = start;
      return none;
    }
  };
  if (o.matcher == EstimatorKind::Icp) {
    const IcpResult r = icp(prior);
    if (converged != nullptr) *converged = r.converged;
    return r.pose;
  }
  // The reference scan as a map whose world frame is the reference robot's frame.
  // Its margin keeps the whole search window on the map.
  const double half_xy = o.prior_noise_xy + o.window_margin_xy;
  OccupancyMap map = scan_occupancy_map(reference, o.map_resolution,
                                        0.5 + std::hypot(prior.x, prior.y) + 1.5 * half_xy);
  // The current scan's max range cut to its farthest return: the padding then covers what
  // the scan reaches, not the logger's 80 m "no return".
  RangeScan cur = current;
  double farthest = 0.0;
  for (const auto& p : cur_points) farthest = std::max(farthest, p.norm());
  cur.max_range = std::min(cur.max_range, farthest + o.map_resolution);
  CorrelationOptions co = o.correlation;
  co.resolution = o.map_resolution;
  co.reach_m = cur.max_range;
  const CorrelationEstimator estimator(std::move(map), co);
  Observation obs;
  obs.scan = cur;
  SearchWindow w = estimator.global_window(obs);  // for its heading step
  w.center = prior;
  w.half_xy = half_xy;
  w.half_theta = o.prior_noise_theta + o.window_margin_theta;
  w.step_xy = o.map_resolution;
  const Pose2 coarse = estimator.estimate(obs, w).pose;
  if (o.matcher == EstimatorKind::Correlation) return coarse;
  const IcpResult r = icp(coarse);
  if (r.converged && std::hypot(r.pose.x - coarse.x, r.pose.y - coarse.y) <= o.refine_max_shift_m &&
      std::abs(normalize_angle(r.pose.theta - coarse.theta)) <= o.refine_max_turn_rad) {
    return r.pose;
  }
  return coarse;
}

RelationEvalReport evaluate_relations(const CarmenLog& log, const std::vector<RelationPair>& pairs,
                                      const RelationEvalOptions& o) {
  if (pairs.empty()) throw Error("relations: no relation falls on two scans of the log");
  Rng rng(o.seed);
  std::vector<double> trans, rot, ms;
  RelationEvalReport report;
  for (const RelationPair& p : pairs) {
    if (p.first >= log.lasers.size() || p.second >= log.lasers.size()) {
      throw Error("relations: a pair names scan " + std::to_string(std::max(p.first, p.second)) +
                  " of a log of " + std::to_string(log.lasers.size()));
    }
    const LaserRecord& a = log.lasers[p.first];
    const LaserRecord& b = log.lasers[p.second];
    Pose2 prior = relative_pose(a.laser_pose, b.laser_pose);
    prior.x += rng.uniform(-o.prior_noise_xy, o.prior_noise_xy);
    prior.y += rng.uniform(-o.prior_noise_xy, o.prior_noise_xy);
    prior.theta =
        normalize_angle(prior.theta + rng.uniform(-o.prior_noise_theta, o.prior_noise_theta));
    const auto t0 = std::chrono::steady_clock::now();
    bool converged = true;
    const Pose2 estimate = match_pair(a.scan, b.scan, prior, o, &converged);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    // The benchmark's error: the estimate seen from the true motion.
    const Pose2 e = relative_pose(p.relation.motion, estimate);
    const double dt = std::hypot(e.x, e.y), dr = std::abs(e.theta);
    trans.push_back(dt);
    rot.push_back(rad2deg(dr));
    if (!converged) ++report.not_converged;
    if (!converged || dt > o.failure_xy || dr > o.failure_theta) ++report.failures;
  }
  report.pairs = static_cast<int>(pairs.size());
  report.translation_error_m = stats(trans);
  report.rotation_error_deg = stats(rot);
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  report.median_ms = ms[ms.size() / 2];
  return report;
}

}  // namespace gridloc
