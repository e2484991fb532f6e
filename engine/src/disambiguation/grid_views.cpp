#include "gridloc/engine/disambiguation/grid_views.hpp"

#include <cmath>
#include <string>

#include "gridloc/engine/disambiguation/information.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_sim.hpp"

namespace gridloc {
namespace {

void check_inputs(const OccupancyMap& map, const Eigen::Vector2d& r, double range,
                  const ScanEquivalence& options) {
  if (map.width() <= 0 || map.height() <= 0 || !(map.geometry.resolution > 0.0)) {
    throw Error("scan_classes: the map is empty");
  }
  if (!(range > 0.0)) {
    throw Error("scan_classes: range must be positive, got " + std::to_string(range));
  }
  if (!r.allFinite()) throw Error("scan_classes: the point r is not finite");
  if (options.beams < 1) {
    throw Error("scan_classes: beams must be >= 1, got " + std::to_string(options.beams));
  }
  if (!(options.tolerance_m >= 0.0) || !std::isfinite(options.tolerance_m)) {
    throw Error("scan_classes: tolerance_m must be finite and >= 0, got " +
                std::to_string(options.tolerance_m));
  }
  if (!(options.share > 0.0 && options.share <= 1.0)) {
    throw Error("scan_classes: share must be in (0, 1], got " + std::to_string(options.share));
  }
}

/// The scans' range limit: the sensor's, or the map's diagonal when unlimited (seed 002 §IV-B).
double scan_limit(const OccupancyMap& map, double range) {
  if (std::isfinite(range)) return range;
  const GridGeometry& g = map.geometry;
  return std::hypot(g.width, g.height) * g.resolution;
}

/// The noise-free scan predicted from start-frame point r under hypothesis h.
RangeScan predicted_scan(const OccupancyMap& map, const Pose2& h, const Eigen::Vector2d& r,
                         double max_range, int beams) {
  const Eigen::Vector2d world = to_world(h, r);
  return simulate_scan(map, {world.x(), world.y(), h.theta}, beams, max_range, 0.0, 0);
}

/// Whether two scans of the same beams are one view: fewer than share x beams differ.
bool same_view(const RangeScan& a, const RangeScan& b, const ScanEquivalence& options) {
  int differing = 0;
  for (std::size_t k = 0; k < a.ranges.size(); ++k) {
    const bool return_a = a.ranges[k] < a.max_range, return_b = b.ranges[k] < b.max_range;
    const bool apart = return_a && std::abs(a.ranges[k] - b.ranges[k]) > options.tolerance_m;
    if (return_a != return_b || apart) ++differing;
  }
  return differing < options.share * static_cast<double>(a.ranges.size());
}

}  // namespace

std::vector<int> scan_classes(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                              const Eigen::Vector2d& r, double range,
                              const ScanEquivalence& options) {
  check_inputs(map, r, range, options);
  const double max_range = scan_limit(map, range);
  std::vector<RangeScan> firsts;  // each class's first member's scan
  std::vector<int> classes;
  classes.reserve(hypotheses.size());
  for (const Pose2& h : hypotheses) {
    RangeScan scan = predicted_scan(map, h, r, max_range, options.beams);
    int found = -1;
    for (std::size_t c = 0; c < firsts.size() && found < 0; ++c) {
      if (same_view(firsts[c], scan, options)) found = static_cast<int>(c);
    }
    if (found < 0) {
      found = static_cast<int>(firsts.size());
      firsts.push_back(std::move(scan));
    }
    classes.push_back(found);
  }
  return classes;
}

double grid_info(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                 const Eigen::Vector2d& r, double range, const ScanEquivalence& options) {
  return expected_eliminations(class_sizes(scan_classes(map, hypotheses, r, range, options)));
}

}  // namespace gridloc
