#pragma once
/// The checks a real laser scan's answer gets beyond its score (issues 35 and 19: never
/// confidently wrong). The score counts the returns that land on walls; these read what it
/// cannot: the beams that cross a wall of the map at the answer, and a winner on the edge of
/// the window it was looked for in (the best pose may lie outside it). Each turns a
/// `localized` answer `not localized` and keeps its pose.
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
};

/// Throws gridloc::Error naming the field unless the ratio and the margin are finite and >= 0.
void validate(const ScanChecks& checks);

/// Records Estimate::through_walls (when through_wall_ratio > 0) and applies the checks to
/// `estimate`, the answer to `scan` on `map`. Throws gridloc::Error for bad checks or a scan
/// that fails validate().
void check_scan_answer(Estimate& estimate, const OccupancyMap& map, const RangeScan& scan,
                       const ScanChecks& checks);

}  // namespace gridloc
