#pragma once
/// The SLAM benchmark's evaluation of relative motion (Kümmerle et al. 2009) applied to scan
/// matching: for each ground-truth relation between two scans of a log, estimate the motion
/// from the two scans, starting from the logged motion perturbed by seeded noise, and measure
/// the error of the estimate against the relation.
#include <cstdint>
#include <string>
#include <vector>

#include "gridloc/engine/robust_icp.hpp"
#include "gridloc/sensors/carmen_log.hpp"
#include "gridloc/sensors/slam_relations.hpp"

namespace gridloc {

struct RelationEvalOptions {
  std::uint64_t seed = 1;
  /// The prior is the logged motion (the logs hold SLAM-corrected poses, not raw odometry)
  /// plus uniform noise within these bounds on x, y (m) and theta (rad).
  double prior_noise_xy = 0.3;
  double prior_noise_theta = 0.174532925199;  ///< 10 deg
  /// A pair fails when the matcher does not converge or its error exceeds these.
  double failure_xy = 0.2;
  double failure_theta = 0.0872664625997;  ///< 5 deg
  IcpOptions icp;
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
  double median_ms = 0.0;  ///< per match
};

/// The points of a scan's returns (range < max_range) in its robot frame, in beam order.
std::vector<Eigen::Vector2d> scan_returns(const RangeScan& scan);

/// The relative pose b in a's frame: a^-1 * b.
Pose2 relative_pose(const Pose2& a, const Pose2& b);

/// Matches every pair with robust ICP (match_scans: the scan at t1 is the reference) and
/// reports the errors. Throws gridloc::Error for no pairs or a pair index outside the log.
RelationEvalReport evaluate_relations_icp(const CarmenLog& log,
                                          const std::vector<RelationPair>& pairs,
                                          const RelationEvalOptions& options = {});

}  // namespace gridloc
