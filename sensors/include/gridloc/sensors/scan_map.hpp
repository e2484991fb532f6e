#pragma once
/// A local occupancy map built from one scan, so a scan can serve as the "known map" of the
/// correlation search (scan-to-scan matching of the SLAM relations, issues 5 and 30).
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// How scan_occupancy_map draws a scan.
struct ScanMapOptions {
  double resolution = 0.05;  ///< cell side (m)
  double margin_m = 0.5;     ///< the map spans the returns plus this
  /// Consecutive returns closer than the adaptive breakpoint gap (join_gap_m plus the
  /// range times breakpoint_growth(beam step, join_grazing_rad)) are one wall, and the cells
  /// between them are Occupied too: a wall seen at a slant by 1-degree beams has returns
  /// 10-30 cm apart, and a scan matched on returns alone fits the gaps as well as the walls
  /// (issue 30: Intel's 106 relations over 5 seeds, correlation + ICP 24 -> 17 failures).
  bool join_returns = true;
  double join_gap_m = 0.05;
  double join_grazing_rad = 0.174532925199;  ///< 10 deg
};

/// The map the scan sees from the origin (robot pose 0, 0, 0 = the map's world frame): each
/// return's cell Occupied (with the wall between joined returns), the cells its beam
/// crossed Free, everything else Unknown (beams without a return leave no trace: their free
/// length is unknown). Throws gridloc::Error for a non-positive resolution, a negative
/// margin, join gap or grazing angle, or a scan that fails validate().
OccupancyMap scan_occupancy_map(const RangeScan& scan, const ScanMapOptions& options);

/// scan_occupancy_map with each return alone (join_returns false).
OccupancyMap scan_occupancy_map(const RangeScan& scan, double resolution, double margin_m = 0.5);

}  // namespace gridloc
