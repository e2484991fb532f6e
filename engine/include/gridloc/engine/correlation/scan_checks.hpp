#pragma once
/// The checks a real laser scan's answer gets beyond its score (issues 35 and 19: never
/// confidently wrong). The score counts the returns that land on walls; these read what it
/// cannot: the beams that cross a wall of the map at the answer, and a winner on the edge of
/// the window it was looked for in (the best pose may lie outside it), and a second place
/// nearly as good. Each turns a `localized` answer `not localized` (the last `ambiguous`) and
/// keeps its pose.
#include "gridloc/engine/estimate.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

struct ScanChecks {
  /// A `localized` answer whose returns cross a wall of the map (more than
  /// through_wall_margin_m before their end) this share of its fit or more
  /// (Estimate::through_walls >= through_wall_ratio * normalized_score) is `not localized`;
  /// 0: no check (CoarseToFineOptions::through_wall_ratio says how it was chosen).
  double through_wall_ratio = 0.7;
  double through_wall_margin_m = 0.3;  ///< the pose's and the map's blur (m)
  /// A `localized` answer whose winner lies on its window's edge (Estimate::on_window_edge)
  /// is `not localized`, as the ICP estimator's is.
  bool edge_not_localized = true;
  /// A `localized` answer with a second place among its alternatives scoring at least
  /// close_second_ratio of the winner and farther than close_second_m from it, while its
  /// returns cross walls (through_walls >= close_second_through_walls) and its confidence
  /// stays below close_second_confidence, is `ambiguous`: a corridor whose doors repeat along
  /// it fits a slid scan nearly as well (issue 19; fitted on 330 held-out windowed scans,
  /// checked on 330 more: README). 0 ratio: no check. It reads through_walls, so it needs the
  /// wall check (through_wall_ratio > 0): without it no answer is ambiguous by this rule.
  double close_second_ratio = 0.88;
  double close_second_m = 0.3;
  double close_second_through_walls = 0.02;
  double close_second_confidence = 0.5;
};

/// Throws gridloc::Error naming the field unless the ratios, shares and distances are finite
/// and >= 0 (close_second_ratio at most 1).
void validate(const ScanChecks& checks);

/// Records Estimate::through_walls (when through_wall_ratio > 0) and applies the checks to
/// `estimate`, the answer to `scan` on `map`. Throws gridloc::Error for bad checks or a scan
/// that fails validate().
void check_scan_answer(Estimate& estimate, const OccupancyMap& map, const RangeScan& scan,
                       const ScanChecks& checks);

}  // namespace gridloc
