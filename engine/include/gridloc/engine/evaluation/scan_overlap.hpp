#pragma once
/// How much two scans see of the same walls (issue 30): the share of one scan's returns that
/// lie near the other's at their true relative pose. A matcher cannot be asked to match a
/// pair that shares little: the failures of the relations protocol are reported per band of
/// this measure.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// The share (0..1) of `current`'s points that lie within `radius_m` of one of
/// `reference`'s once moved by `motion` (the pose of the current scan's frame in the
/// reference's). 0 when `current` is empty. Exact (every pair of points is compared).
double scan_overlap(const std::vector<Eigen::Vector2d>& reference,
                    const std::vector<Eigen::Vector2d>& current, const Pose2& motion,
                    double radius_m = 0.2);

/// Pairs and failures in one row of a failure table.
struct FailureRow {
  std::string label;  ///< the band ("0.4-0.6") or the verdict ("localized", "none" for ICP)
  int pairs = 0;
  int failures = 0;
};

/// Throws gridloc::Error unless `edges` rise strictly inside (0, 1) (the failure table's
/// band edges).
void check_band_edges(const std::vector<double>& edges);

/// The overlap bands between `edges` (ascending, inside (0, 1)): "0-e0", "e0-e1", ...,
/// "eN-1" (%g: "0-0.2", "0.8-1"), each row counting the `overlaps` in [low, high) (the last
/// includes 1) and the `failed` among them. Throws gridloc::Error for unsorted or out-of-range
/// edges or sizes that differ.
std::vector<FailureRow> failures_by_band(const std::vector<double>& overlaps,
                                         const std::vector<bool>& failed,
                                         const std::vector<double>& edges);

}  // namespace gridloc
