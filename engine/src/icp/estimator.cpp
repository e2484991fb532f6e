#include "gridloc/engine/icp/estimator.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

const RangeScan& scan_of(const Observation& observation, const char* who) {
  if (!observation.scan) {
    throw Error(std::string(who) +
                ": needs a laser scan (--scan); ICP finds no tangents in a sonar ring's echoes");
  }
  validate(*observation.scan);
  return *observation.scan;
}

/// The pose lies outside the window: beyond its half sizes in the map's grid frame (the
/// frame the correlation search's lattice lies in), or its heading beyond half_theta.
bool outside(const Pose2& pose, const SearchWindow& w, const GridGeometry& g) {
  const Pose2 p = g.to_grid_frame(pose), c = g.to_grid_frame(w.center);
  return std::abs(p.x - c.x) > w.half_xy || std::abs(p.y - c.y) > w.half_xy ||
         std::abs(normalize_angle(pose.theta - w.center.theta)) > w.half_theta;
}

void check_verdict(const VerdictOptions& v) {
  if (!(v.spread_scale_m > 0.0) || !std::isfinite(v.spread_scale_m)) {
    throw Error("VerdictOptions.spread_scale_m must be positive and finite, got " +
                std::to_string(v.spread_scale_m));
  }
  if (!(v.localized_confidence >= 0.0 && v.localized_confidence <= 1.0)) {
    throw Error("VerdictOptions.localized_confidence must lie in [0, 1], got " +
                std::to_string(v.localized_confidence));
  }
}

}  // namespace

IcpEstimator::IcpEstimator(const OccupancyMap& map, IcpEstimatorOptions options)
    : contour_(map, options.contour), geometry_(map.geometry), options_(options) {
  validate(options_.icp);  // fails at construction, not at the first scan
  check_verdict(options_.verdict);
}

Estimate IcpEstimator::estimate(const Observation& observation, const SearchWindow& window) const {
  validate(window);
  const auto t0 = std::chrono::steady_clock::now();
  Estimate e = to_estimate(match(observation, window.center), window);
  e.stats.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

IcpResult IcpEstimator::match(const Observation& observation, const Pose2& start) const {
  const RangeScan& scan = scan_of(observation, "icp estimator");
  const auto points = scan_returns(scan);
  try {
    return match_scan_to_map(contour_, points, start, options_.icp);
  } catch (const Error&) {
    // The scan and options are valid (checked above and at construction): what is left is a
    // scan ICP cannot use, too few returns in segments. Not an input error but a failure to
    // localize with ICP: a not converged result at the start, nothing constrained.
    IcpResult none;
    none.pose = start;
    none.covariance =
        Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()).asDiagonal();
    return none;
  }
}

Estimate IcpEstimator::to_estimate(const IcpResult& r, const SearchWindow& window) const {
  Estimate e;
  e.pose = e.lattice_pose = r.pose;
  ConfidenceParts& parts = e.confidence_parts;
  parts.fit = r.matching_points == 0
                  ? 0.0
                  : static_cast<double>(r.fitting_pairs) / static_cast<double>(r.matching_points);
  parts.agreement = 1.0;
  parts.distinctness = 1.0;
  const double spread = std::sqrt(r.covariance(0, 0) + r.covariance(1, 1));
  parts.sharpness = std::isfinite(spread) ? std::exp(-spread / options_.verdict.spread_scale_m) : 0;
  e.score = e.normalized_score = parts.fit;
  e.second_score = std::numeric_limits<double>::quiet_NaN();
  e.confidence = r.converged ? parts.fit * parts.sharpness : 0.0;
  e.agreement = std::numeric_limits<double>::quiet_NaN();
  e.covariance = r.covariance;
  e.on_window_edge = outside(r.pose, window, geometry_);
  e.verdict = !e.on_window_edge && e.confidence >= options_.verdict.localized_confidence
                  ? Verdict::Localized
                  : Verdict::NotLocalized;
  e.alternatives = {{e.pose, e.score}};
  e.stats.poses_scored = r.iterations;
  e.stats.cells_scored =
      static_cast<long long>(r.iterations) * static_cast<long long>(r.matching_points);
  e.stats.levels = 1;
  e.stats.proven_optimal = false;
  e.stats.upper_bound = std::numeric_limits<double>::quiet_NaN();
  return e;
}

CorrelationIcpEstimator::CorrelationIcpEstimator(
    std::shared_ptr<const CorrelationEstimator> correlation,
    std::shared_ptr<const IcpEstimator> icp, CorrelationIcpOptions options)
    : correlation_(std::move(correlation)), icp_(std::move(icp)), options_(options) {
  if (!correlation_ || !icp_) throw Error("CorrelationIcpEstimator: needs both estimators");
}

Estimate CorrelationIcpEstimator::estimate(const Observation& observation,
                                           const SearchWindow& window) const {
  const auto t0 = std::chrono::steady_clock::now();
  scan_of(observation, "correlation+icp estimator");
  Estimate e = correlation_->estimate(observation, window);
  const IcpResult fine = icp_->match(observation, e.pose);
  if (fine.converged &&
      std::hypot(fine.pose.x - e.pose.x, fine.pose.y - e.pose.y) <= options_.max_shift_m &&
      std::abs(normalize_angle(fine.pose.theta - e.pose.theta)) <= options_.max_turn_rad) {
    e.pose = fine.pose;
  }
  e.stats.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

}  // namespace gridloc
