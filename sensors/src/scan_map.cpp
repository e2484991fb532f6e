#include "gridloc/sensors/scan_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

OccupancyMap scan_occupancy_map(const RangeScan& scan, double resolution, double margin_m) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("scan_occupancy_map: resolution must be positive, got " +
                std::to_string(resolution));
  }
  if (!(margin_m >= 0.0) || !std::isfinite(margin_m)) {
    throw Error("scan_occupancy_map: margin must be >= 0, got " + std::to_string(margin_m));
  }
  validate(scan);
  double lo_x = 0.0, lo_y = 0.0, hi_x = 0.0, hi_y = 0.0;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (!(r < scan.max_range) || r <= 0.0) continue;
    const double x = r * std::cos(scan.angles[k]), y = r * std::sin(scan.angles[k]);
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x);
    lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  }
  GridGeometry g;
  g.resolution = resolution;
  g.origin = {lo_x - margin_m, lo_y - margin_m};
  g.width = static_cast<int>(std::ceil((hi_x - lo_x + 2 * margin_m) / resolution)) + 1;
  g.height = static_cast<int>(std::ceil((hi_y - lo_y + 2 * margin_m) / resolution)) + 1;
  OccupancyMap map(g, CellState::Unknown);
  std::vector<std::pair<int, int>> hits;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (!(r < scan.max_range) || r <= 0.0) continue;
    const double c = std::cos(scan.angles[k]), s = std::sin(scan.angles[k]);
    // Free cells: samples every half cell up to one cell short of the return.
    const int steps = static_cast<int>((r - resolution) / (0.5 * resolution));
    for (int i = 0; i <= steps; ++i) {
      const double d = 0.5 * resolution * i;
      const Cell cell = g.cell_of(d * c - g.origin.x(), d * s - g.origin.y());
      if (g.contains(cell.ix, cell.iy)) map.at(cell.ix, cell.iy) = CellState::Free;
    }
    const Cell hit = g.cell_of(r * c - g.origin.x(), r * s - g.origin.y());
    if (g.contains(hit.ix, hit.iy)) hits.emplace_back(hit.ix, hit.iy);
  }
  // Returns win over free space another beam crossed.
  for (const auto& [x, y] : hits) map.at(x, y) = CellState::Occupied;
  return map;
}

}  // namespace gridloc
