#pragma once
/// Predicted sensing on occupancy maps, the grid twin of seed 002's congruent views (§IV-A):
/// two hypotheses are equivalent at a start-frame point r when the noise-free laser scans
/// predicted from r under each (same heading, same range limit, §IV-B) agree within a
/// tolerance on all but a small share of the beams.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/grid.hpp"

namespace gridloc {

/// When two predicted scans count as the same view.
struct ScanEquivalence {
  int beams = 90;            ///< beams of each predicted 360-degree scan (>= 1)
  double tolerance_m = 0.2;  ///< ranges differing by more than this (m) differ (>= 0)
  double share = 0.1;        ///< views differ when at least this share of beams differ, (0, 1]
};

/// The equivalence class of each hypothesis at start-frame point r (m): classes numbered
/// 0, 1, ... in order of first appearance, each hypothesis compared with each class's first
/// member. A hypothesis's scan is simulate_scan from to_world(h, r) with heading h.theta,
/// sigma 0, max range `range` (m; +inf: the map's diagonal). A beam with no return in both
/// scans is equal, one with a return and one without differs. Throws gridloc::Error for an
/// empty map, a range that is not positive, a point that is not finite, or bad options.
std::vector<int> scan_classes(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                              const Eigen::Vector2d& r, double range,
                              const ScanEquivalence& options = {});

/// Seed 002's info(r) = sum over classes b of (s_b / k)(k - s_b): the expected number of
/// hypotheses a scan at r eliminates, all k equally likely (§IV-A), from scan_classes.
double grid_info(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                 const Eigen::Vector2d& r, double range, const ScanEquivalence& options = {});

}  // namespace gridloc
