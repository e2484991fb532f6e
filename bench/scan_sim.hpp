#pragma once
/// Synthetic laser scans and maps for the scaling benchmarks (bench_scaling.cpp). The engine
/// has no laser simulator; these stay in bench/ because only the benchmarks need them.
#include <cstdint>

#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc::bench {

/// A 360-degree scan of `beams` beams from world pose `pose` on `map`: beam k at angle
/// -pi + 2 pi k / beams (robot frame), range = distance to the first Occupied cell along
/// the beam (exact grid traversal; Unknown cells are transparent, as in simulate_sonar),
/// plus Gaussian noise of sigma_m drawn from Rng(seed). No hit within max_range, or a beam
/// leaving the map, reads exactly max_range (no return).
RangeScan simulate_scan(const OccupancyMap& map, const Pose2& pose, int beams, double max_range,
                        double sigma_m, std::uint64_t seed);

/// A rooms_x x rooms_y grid of 5 m x 4 m rooms at 0.05 m: 0.15 m walls, a 0.9 m door in every
/// wall between two rooms, 3 free-standing blocks (0.3 to 1.0 m) per room and 0.5 m of
/// unknown margin. Room (i, j), its blocks and its doors depend only on (i, j) and `seed`, so
/// a smaller map's rooms reappear in a bigger one; the blocks make every room distinct, so a
/// global search has no look-alike to confuse it with.
/// Origin (0, 0): room (0, 0)'s interior starts at (0.15, 0.15) m.
OccupancyMap synthetic_rooms(int rooms_x, int rooms_y, std::uint64_t seed);

/// A free pose in room (0, 0) of synthetic_rooms(), kept clear of the blocks.
Pose2 synthetic_rooms_truth();

}  // namespace gridloc::bench
