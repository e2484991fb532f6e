#pragma once
/// A local occupancy map built from one scan, so a scan can serve as the "known map" of the
/// correlation search (scan-to-scan matching of the SLAM relations, issue 5).
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// The map the scan sees from the origin (robot pose 0, 0, 0 = the map's world frame): each
/// return's cell Occupied, the cells its beam crossed Free, everything else Unknown (beams
/// without a return leave no trace: their free length is unknown). Cells of `resolution` m,
/// the map spans the returns plus `margin_m`. Throws gridloc::Error for a non-positive
/// resolution, a negative margin or a scan that fails validate().
OccupancyMap scan_occupancy_map(const RangeScan& scan, double resolution, double margin_m = 0.5);

}  // namespace gridloc
