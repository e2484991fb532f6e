#pragma once
/// The SLAM benchmark's evaluation of relative motion (Kümmerle et al. 2009) applied to scan
/// matching: for each ground-truth relation between two scans of a log, estimate the motion
/// from the two scans, starting from the logged motion perturbed by seeded noise, and measure
/// the error of the estimate against the relation.
#include <cstdint>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/estimator.hpp"
#include "gridloc/engine/icp/robust_icp.hpp"
#include "gridloc/sensors/carmen_log.hpp"
#include "gridloc/sensors/slam_relations.hpp"

namespace gridloc {

struct RelationEvalOptions {
  /// How a relation's two scans are matched: Icp (match_scans from the prior), Correlation
  /// (the search of the current scan on the reference scan's map) or CorrelationIcp (the
  /// search, then ICP from its winner).
  EstimatorKind matcher = EstimatorKind::Icp;
  std::uint64_t seed = 1;
  /// The prior is the logged motion (the logs hold SLAM-corrected poses, not raw odometry)
  /// plus uniform noise within these bounds on x, y (m) and theta (rad).
  double prior_noise_xy = 0.3;
  double prior_noise_theta = 0.174532925199;  ///< 10 deg
  /// A pair fails when the matcher does not converge or its error exceeds these.
  double failure_xy = 0.2;
  double failure_theta = 0.0872664625997;  ///< 5 deg
  IcpOptions icp;
  /// The correlation matchers: the reference scan becomes a map of this resolution
  /// (scan_occupancy_map), searched with `correlation` (branch and bound, hits) over a window
  /// around the prior covering its noise plus window_margin_xy and window_margin_theta, in
  /// heading steps that move the farthest return by about a cell.
  double map_resolution = 0.05;
  double window_margin_xy = 0.1;
  double window_margin_theta = 0.0349065850399;  ///< 2 deg
  CorrelationOptions correlation;
  /// Correlation + ICP: ICP's pose is kept when it converged within these of the search's.
  double refine_max_shift_m = 0.3;
  double refine_max_turn_rad = 0.0872664625997;  ///< 5 deg
};

/// Mean and standard deviation.
struct ErrorStats {
  double mean = 0.0;
  double std = 0.0;
};

struct RelationEvalReport {
  int pairs = 0;
  ErrorStats translation_error_m;  ///< |translation of relation^-1 * estimate|, over all pairs
  ErrorStats rotation_error_deg;   ///< |rotation of relation^-1 * estimate|
  int failures = 0;
  int not_converged = 0;   ///< ICP alone: matches that did not converge (counted as failures)
  double median_ms = 0.0;  ///< per match, the reference map's construction included
};

/// The motion of `current` in `reference`'s frame by `options.matcher`, from `prior`.
/// `converged`: for Icp, whether ICP converged (false at the iteration limit, with too few
/// pairs, or on a scan ICP cannot use, whose estimate is then the prior); Correlation and
/// CorrelationIcp always answer (true; CorrelationIcp keeps the search's pose when ICP fails).
/// Throws gridloc::Error for a scan that fails validate().
Pose2 match_pair(const RangeScan& reference, const RangeScan& current, const Pose2& prior,
                 const RelationEvalOptions& options, bool* converged = nullptr);

/// Matches every pair by options.matcher (the scan at t1 is the reference) and reports the
/// errors. Throws gridloc::Error for no pairs or a pair index outside the log.
RelationEvalReport evaluate_relations(const CarmenLog& log, const std::vector<RelationPair>& pairs,
                                      const RelationEvalOptions& options = {});

}  // namespace gridloc
