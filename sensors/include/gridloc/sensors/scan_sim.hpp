#pragma once
/// A laser scan simulator on an occupancy map: exact grid ray casting plus seeded Gaussian
/// range noise. Used by the benchmarks and by the evaluation's laser trials.
#include <cstdint>

#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// A 360-degree scan of `beams` beams from world pose `pose` on `map`: beam k at angle
/// -pi + 2 pi k / beams (robot frame), range = distance to the first Occupied cell along
/// the beam (exact grid traversal; Unknown cells are transparent, as in simulate_sonar),
/// plus Gaussian noise of sigma_m drawn from Rng(seed), clamped to [0, max_range]. No hit
/// within max_range, or a beam leaving the map, reads exactly max_range (no return).
/// Throws gridloc::Error naming the field for beams < 1, a max_range that is not positive and
/// finite, a sigma_m that is negative or not finite, or a pose that is not finite.
RangeScan simulate_scan(const OccupancyMap& map, const Pose2& pose, int beams, double max_range,
                        double sigma_m, std::uint64_t seed);

}  // namespace gridloc
