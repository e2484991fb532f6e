#pragma once
/// Synthetic maps for the scaling benchmarks (bench_scaling.cpp, bench_kernels.cpp); they stay in
/// bench/ because only the benchmarks need them. The laser simulator that scans them,
/// simulate_scan, is in the sensors library (gridloc/sensors/scan_sim.hpp).
#include <cstdint>

#include "gridloc/grids/grid.hpp"

namespace gridloc::bench {

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
