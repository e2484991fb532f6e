#include "gridloc/sensors/scan_map.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/breakpoints.hpp"

namespace gridloc {
namespace {

void check(const ScanMapOptions& options) {
  auto require = [](bool ok, const char* what, double value) {
    if (!ok)
      throw Error(std::string("scan_occupancy_map: ") + what + ", got " + std::to_string(value));
  };
  const auto finite = [](double v) { return std::isfinite(v); };
  require(options.resolution > 0.0 && finite(options.resolution), "resolution must be positive",
          options.resolution);
  require(options.margin_m >= 0.0 && finite(options.margin_m), "margin must be >= 0",
          options.margin_m);
  require(options.join_gap_m >= 0.0 && finite(options.join_gap_m), "join_gap_m must be >= 0",
          options.join_gap_m);
  check_grazing_angle(options.join_grazing_rad, "scan_occupancy_map: join_grazing_rad");
}

bool is_return(const RangeScan& scan, std::size_t k) {
  return scan.ranges[k] < scan.max_range && scan.ranges[k] > 0.0;
}

Eigen::Vector2d return_point(const RangeScan& scan, std::size_t k) {
  return {scan.ranges[k] * std::cos(scan.angles[k]), scan.ranges[k] * std::sin(scan.angles[k])};
}

/// A map covering the scan's returns and the origin plus `margin_m`, every cell Unknown.
OccupancyMap unknown_map(const RangeScan& scan, double resolution, double margin_m) {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    if (!is_return(scan, k)) continue;
    lo = lo.cwiseMin(return_point(scan, k));
    hi = hi.cwiseMax(return_point(scan, k));
  }
  GridGeometry g;
  g.resolution = resolution;
  g.origin = {lo.x() - margin_m, lo.y() - margin_m};
  g.width = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin_m) / resolution)) + 1;
  g.height = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin_m) / resolution)) + 1;
  return OccupancyMap(g, CellState::Unknown);
}

/// The cells of the segment from `a` to `b`, sampled every half cell (both ends included).
void add_segment_cells(const GridGeometry& g, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       std::vector<std::pair<int, int>>& cells) {
  const int samples =
      std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.5 * g.resolution))));
  for (int i = 0; i <= samples; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / samples);
    const Cell cell = g.cell_of(p.x() - g.origin.x(), p.y() - g.origin.y());
    if (g.contains(cell.ix, cell.iy)) cells.emplace_back(cell.ix, cell.iy);
  }
}

/// The cells of the walls between consecutive returns closer than the breakpoint gap.
std::vector<std::pair<int, int>> joined_cells(const RangeScan& scan, const GridGeometry& g,
                                              const ScanMapOptions& options) {
  std::vector<std::pair<int, int>> cells;
  for (std::size_t k = 1; k < scan.ranges.size(); ++k) {
    if (!is_return(scan, k - 1) || !is_return(scan, k)) continue;
    const double step = std::abs(scan.angles[k] - scan.angles[k - 1]);
    const double gap =
        options.join_gap_m + scan.ranges[k - 1] * breakpoint_growth(step, options.join_grazing_rad);
    const Eigen::Vector2d a = return_point(scan, k - 1), b = return_point(scan, k);
    if ((b - a).norm() <= gap) add_segment_cells(g, a, b, cells);
  }
  return cells;
}

}  // namespace

OccupancyMap scan_occupancy_map(const RangeScan& scan, const ScanMapOptions& options) {
  check(options);
  validate(scan);
  OccupancyMap map = unknown_map(scan, options.resolution, options.margin_m);
  const GridGeometry& g = map.geometry;
  std::vector<std::pair<int, int>> walls;
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    if (!is_return(scan, k)) continue;
    // Free cells: samples every half cell up to one cell short of the return.
    const double r = scan.ranges[k];
    const double c = std::cos(scan.angles[k]), s = std::sin(scan.angles[k]);
    const int steps = static_cast<int>((r - g.resolution) / (0.5 * g.resolution));
    for (int i = 0; i <= steps; ++i) {
      const double d = 0.5 * g.resolution * i;
      const Cell cell = g.cell_of(d * c - g.origin.x(), d * s - g.origin.y());
      if (g.contains(cell.ix, cell.iy)) map.at(cell.ix, cell.iy) = CellState::Free;
    }
    const Eigen::Vector2d hit = return_point(scan, k);
    const Cell cell = g.cell_of(hit.x() - g.origin.x(), hit.y() - g.origin.y());
    if (g.contains(cell.ix, cell.iy)) walls.emplace_back(cell.ix, cell.iy);
  }
  if (options.join_returns) {
    const auto joined = joined_cells(scan, g, options);
    walls.insert(walls.end(), joined.begin(), joined.end());
  }
  // Returns (and the walls between them) win over free space another beam crossed.
  for (const auto& [x, y] : walls) map.at(x, y) = CellState::Occupied;
  return map;
}

OccupancyMap scan_occupancy_map(const RangeScan& scan, double resolution, double margin_m) {
  ScanMapOptions options;
  options.resolution = resolution;
  options.margin_m = margin_m;
  options.join_returns = false;
  return scan_occupancy_map(scan, options);
}

}  // namespace gridloc
