#pragma once
/// Occupancy maps drawn from a laser log whose poses are right (a SLAM-corrected CARMEN log):
/// every beam is cast from its scan's logged laser pose, the cells it crosses counted as
/// passes and its end cell as a hit, and each cell classified from its counts. This gives the
/// real buildings of ../shared/datasets/acschaefer_ple a map drawn from part of their own log.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/sensors/carmen_log.hpp"

namespace gridloc {

struct LogMapOptions {
  double resolution = 0.05;  ///< cell size (m)
  /// Returns farther than this (m) count as no return. A far return's angular error grows
  /// with its range (0.5 degree is 17 cm at 20 m), and several of these logs report "no
  /// return" as 32.8, 50 or 51.2 m rather than as the scanner's 81.9 m.
  double max_range_m = 20.0;
  /// Beams without a return (range >= the scan's max range or > max_range_m) are drawn free
  /// up to this distance (m), without an end; 0 skips them. Skipped by default: in these logs
  /// a missing return is as often glass, a window or a dark surface as open space, and drawn
  /// free they streak through the walls.
  double no_return_free_m = 0.0;
  double margin_m = 1.0;  ///< unknown border around everything drawn (m)
  /// A cell is Occupied when at least min_hits beams ended in it and hits / (hits + passes)
  /// is at least occupied_ratio; beams through a wall cell at a grazing angle pass it, and
  /// people walking by are hit a few times and passed through many times.
  int min_hits = 1;
  double occupied_ratio = 0.25;
  /// A cell that is not Occupied is Free when at least min_passes beams crossed it, else
  /// Unknown.
  int min_passes = 1;
  /// The map may hold at most limits.max_cells cells, and need at most limits.max_memory_mb
  /// while drawing (5 bytes a cell: 250 MB at the default 50 M cells; the largest of
  /// acschaefer_ple, freiburg-campus at 5 cm, has 22 million), so that a log with a wild pose
  /// cannot eat the memory.
  ResourceLimits limits;
};

/// Checks `options`; throws gridloc::Error naming the field.
void validate(const LogMapOptions& options);

/// The map drawn by the scans `indices` of `lasers` (see the file comment). It spans the drawn
/// beams (and the first scan's laser position) plus options.margin_m, in the log's frame
/// (yaw 0). Throws gridloc::Error for no index, an index out of range, a laser pose that is not
/// finite, a scan that fails validate() (a scan without any return is accepted: it draws
/// nothing by default), a map that would exceed options.limits.max_cells or max_memory_mb
/// (the message gives its size), or bad options.
OccupancyMap map_from_log(const std::vector<LaserRecord>& lasers,
                          const std::vector<std::size_t>& indices,
                          const LogMapOptions& options = {});

/// map_from_log of `log`'s laser records.
OccupancyMap map_from_log(const CarmenLog& log, const std::vector<std::size_t>& indices,
                          const LogMapOptions& options = {});

/// How many cells of `map` are in each state.
struct CellCounts {
  std::size_t occupied = 0;
  std::size_t free = 0;
  std::size_t unknown = 0;
};
CellCounts count_cells(const OccupancyMap& map);

}  // namespace gridloc
