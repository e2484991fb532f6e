#pragma once
// The runs of a short-range scan and the straight walls fitted along them (seed 003 ch. VI B;
// internal to extract_features).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gridloc/engine/team/scan_features.hpp"

namespace gridloc::team_detail {

/// The reading next to one end of a run, in scan order (just before its first return or just
/// after its last).
struct RunNeighbour {
  bool exists = false;    ///< false at the edge of a scan that is no full turn
  bool saturated = true;  ///< no return (a range at or above the max range)
  Eigen::Vector2d beam = Eigen::Vector2d::UnitX();  ///< unit direction of its beam
  double range = 0.0;                               ///< its reading (m)
};

/// Consecutive returns (scan frame, m) with no saturated reading and no jump over gap_m
/// between them, in scan order. A closed run is the whole turn: its last point is followed by
/// its first, and indices wrap (at()).
struct ScanRun {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
  RunNeighbour before, after;  ///< the readings around an open run
  /// Point i, indices taken modulo the run's size (negative ones too).
  const Eigen::Vector2d& at(std::ptrdiff_t i) const;
  std::ptrdiff_t size() const { return static_cast<std::ptrdiff_t>(points.size()); }
};

/// The runs of `scan`, its readings ordered by angle (normalized to [0, 2 pi)); the scan is a
/// full turn (its last reading next to its first) when the gap from its last angle round to
/// its first is no wider than 1.5 of its widest step. The scan must have passed the checks of
/// extract_features.
std::vector<ScanRun> scan_runs(const RangeScan& scan, double gap_m);

/// A total-least-squares line: centroid and unit direction (pointing along the scan).
struct FittedLine {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  /// [0 0 1] x direction (seed 003 eq. 3.6): towards the robot for a wall seen along the scan.
  Eigen::Vector2d normal() const { return {-direction.y(), direction.x()}; }
  double distance(const Eigen::Vector2d& p) const;          ///< unsigned, m
  Eigen::Vector2d project(const Eigen::Vector2d& p) const;  ///< the nearest point of the line
};

/// A straight wall along a run: run points [begin, end) (indices wrap in a closed run).
struct WallPiece {
  std::ptrdiff_t begin = 0, end = 0;
  FittedLine line;
  double sum_squares = 0.0;   ///< of the points' distances from the line (m^2)
  double max_distance = 0.0;  ///< the farthest point's distance from the line (m)
  int count() const { return static_cast<int>(end - begin); }
};

/// The fit of run points [begin, end): direction oriented from the first point to the last.
WallPiece fit_piece(const ScanRun& run, std::ptrdiff_t begin, std::ptrdiff_t end);

/// The walls of a run by split-and-merge (split_m), fitted, without the pieces shorter than
/// min_wall_points or min_wall_m; in run order. In a closed run the last piece is followed by
/// the first.
std::vector<WallPiece> fitted_walls(const ScanRun& run, const FeatureOptions& options);

}  // namespace gridloc::team_detail
