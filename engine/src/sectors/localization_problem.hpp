#pragma once
// What one localization in the sectors reads and remembers (internal): the checked scan's
// view, the problem every step reads, and the memo of residuals and polished poses.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "gridloc/engine/sectors/localization.hpp"
#include "pose_fit.hpp"

namespace gridloc::sectors_detail {

/// Throws gridloc::Error unless the scan is a full counter-clockwise turn (seed 000 §3.1).
void check_full_turn(const RangeScan& scan);

/// The options' ranges; throws gridloc::Error naming them.
void check_options(const SectorLocalizationOptions& options);

/// The scan as the localization reads it: its label, every beam as a point (robot frame, a
/// beam without return at the max range), the beams with a return and their points, and the
/// widest beam step.
struct ScanView {
  const RangeScan& scan;
  ScanLabel label;
  std::vector<Eigen::Vector2d> points;   ///< per beam
  std::vector<int> hits;                 ///< the beams with a return
  std::vector<Eigen::Vector2d> returns;  ///< their points
  double beam_step = 0.0;                ///< rad, at most 0.2
};

/// The scan's label, points, returns and beam step (see ScanView).
ScanView view_scan(const RangeScan& scan, const ScanLabelOptions& label_options);

/// What every step reads: the sectors, the options, the scan and the map's walls.
struct Problem {
  const SectorMap& sectors;
  const SectorLocalizationOptions& options;
  ScanView view;
  std::vector<Wall> walls;
};

/// The two caches of a localization: sectors with alike labels give the same pose from the
/// same vertices many times over (residuals, poses within 1e-9), and many sectors give the
/// same correspondences, hence the same rough pose (polishes, exact poses).
struct PoseMemo {
  std::vector<std::pair<Pose2, double>> residuals;  ///< pose, range_residual(pose, 1)
  std::vector<std::pair<Pose2, Pose2>> polishes;    ///< rough pose, polished pose

  /// range_residual() of every return at `pose`, remembered.
  double residual_at(const Problem& problem, const Pose2& pose);

  /// `rough` polished on the walls, remembered; with `gated`, left rough when the scan
  /// refutes it.
  Pose2 polished(const Problem& problem, const Pose2& rough, bool gated);
};

}  // namespace gridloc::sectors_detail
