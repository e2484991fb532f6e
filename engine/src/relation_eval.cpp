#include "gridloc/engine/relation_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"

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

std::vector<Eigen::Vector2d> scan_returns(const RangeScan& scan) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < scan.ranges.size() && k < scan.angles.size(); ++k) {
    const double r = scan.ranges[k];
    if (r < scan.max_range && r > 0.0) {
      points.emplace_back(r * std::cos(scan.angles[k]), r * std::sin(scan.angles[k]));
    }
  }
  return points;
}

Pose2 relative_pose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, normalize_angle(b.theta - a.theta)};
}

RelationEvalReport evaluate_relations_icp(const CarmenLog& log,
                                          const std::vector<RelationPair>& pairs,
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
    const IcpResult r = match_scans(scan_returns(a.scan), scan_returns(b.scan), prior, o.icp);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    // The benchmark's error: the estimate seen from the true motion.
    const Pose2 e = relative_pose(p.relation.motion, r.pose);
    const double dt = std::hypot(e.x, e.y), dr = std::abs(e.theta);
    trans.push_back(dt);
    rot.push_back(rad2deg(dr));
    if (!r.converged || dt > o.failure_xy || dr > o.failure_theta) ++report.failures;
  }
  report.pairs = static_cast<int>(pairs.size());
  report.translation_error_m = stats(trans);
  report.rotation_error_deg = stats(rot);
  std::nth_element(ms.begin(), ms.begin() + static_cast<std::ptrdiff_t>(ms.size() / 2), ms.end());
  report.median_ms = ms[ms.size() / 2];
  return report;
}

}  // namespace gridloc
