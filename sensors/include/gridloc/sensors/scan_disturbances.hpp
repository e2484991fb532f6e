#pragma once
/// What seed 004 §4's simulation does to clean scans: range noise, and the outliers of
/// "occlusion or appearance of obstacles". Seeded with gridloc::Rng, so every platform draws
/// the same disturbances.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// Adds Gaussian noise of `sigma_m` along the beam to every return (ranges below max_range),
/// kept at 1 mm or more. Throws gridloc::Error for a negative or non-finite sigma.
void add_range_noise(RangeScan& scan, double sigma_m, std::uint64_t seed);

/// Replaces floor(share * n) of the points, chosen at random, by points drawn uniformly in the
/// square of half side `half_side_m` around the robot: spurious returns. Throws gridloc::Error
/// for a share outside [0, 1] or a non-positive half side.
std::vector<Eigen::Vector2d> scatter_outliers(std::vector<Eigen::Vector2d> points, double share,
                                              double half_side_m, std::uint64_t seed);

/// Pulls `share` of the points, in four contiguous runs (one per quarter of the scan), 20-60 %
/// closer to the robot: obstacles that appeared. Throws gridloc::Error for a share outside
/// [0, 1].
std::vector<Eigen::Vector2d> appear_obstacles(std::vector<Eigen::Vector2d> points, double share,
                                              std::uint64_t seed);

}  // namespace gridloc
