#include "gridloc/engine/sector_estimator.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "gridloc/engine/correlation_estimator.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

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

Estimate SectorEstimator::estimate(const Observation& observation,
                                   const SearchWindow& window) const {
  validate(window);
  const auto t0 = std::chrono::steady_clock::now();
  const SectorFix f = fix(observation);
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
  e.alternatives = {{e.pose, e.score}};
  e.stats.poses_scored = f.candidates;
  e.stats.proven_optimal = false;
  e.stats.upper_bound = std::numeric_limits<double>::quiet_NaN();
  e.stats.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

}  // namespace gridloc
