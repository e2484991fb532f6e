#pragma once
/// Resource limits on inputs (issue 14): every file, grid, scan and polygon that enters
/// gridloc is checked against these before it is read or allocated, so that no input can take
/// all of a small robot computer's memory or time. The defaults fit a 2-core, 4 GB machine
/// with room to spare; each is overridable (the CLI's --max-* options name them).
#include <cstdint>
#include <string>

namespace gridloc {

struct ResourceLimits {
  /// Bytes of any one input file (maps, rings, readings, scans, logs, relations).
  double max_file_mb = 1024.0;
  /// Cells of any one grid gridloc builds: a map image, a rasterized polygon map, an OctoMap
  /// slice, a resampled evidence grid, a search grid (50 M: a 350 m square at 5 cm).
  double max_cells = 50e6;
  /// The estimated peak memory of the grids built for one map (all of an estimator's
  /// precomputed grids together), checked before they are allocated.
  double max_memory_mb = 2560.0;
  /// Beams or readings in one scan.
  double max_beams = 100'000;
  /// Vertices of a polygon map (its boundary and obstacles together).
  double max_vertices = 10'000;
  /// Largest absolute coordinate of a map corner, origin or pose (m): beyond it double
  /// precision on a 1 mm lattice, and int cell indices, are no longer guaranteed.
  double max_coordinate_m = 1e6;

  /// Throws gridloc::Error naming the first field that is not a positive finite number.
  void validate() const;
};

/// The option that raises each limit in the gridloc CLI (for messages): "--max-cells", ...
struct LimitNames {
  static constexpr const char* file_mb = "--max-file-mb";
  static constexpr const char* cells = "--max-cells";
  static constexpr const char* memory_mb = "--max-memory-mb";
  static constexpr const char* beams = "--max-beams";
  static constexpr const char* vertices = "--max-vertices";
  static constexpr const char* coordinate_m = "--max-coordinate-m";
};

/// Throws gridloc::Error "<what>: <amount> <unit> exceeds the limit of <limit> <unit> (raise
/// it with <option>)" when amount > limit (or amount is not a number).
void check_limit(double amount, double limit, const std::string& what, const std::string& unit,
                 const char* option);

/// Checks a grid of width x height cells (given as doubles, before any cast to int) against
/// limits.max_cells and the int range; returns width * height. `what` names the grid.
double check_grid_cells(double width, double height, const ResourceLimits& limits,
                        const std::string& what);

/// Checks an estimated allocation of `bytes` against limits.max_memory_mb: "<what> would need
/// about <n> MB, more than the limit of <limit> MB (raise it with --max-memory-mb)".
void check_memory(double bytes, const ResourceLimits& limits, const std::string& what);

/// Checks that `path` names a readable regular file (not a directory or a device) of at most
/// limits.max_file_mb; `what` says what the file is meant to be ("map image", "readings
/// file"). Returns its size in bytes. Throws gridloc::Error naming the path otherwise.
std::uintmax_t check_input_file(const std::string& path, const std::string& what,
                                const ResourceLimits& limits);

/// Reads the whole of an input file checked by check_input_file into a string.
std::string read_input_file(const std::string& path, const std::string& what,
                            const ResourceLimits& limits);

}  // namespace gridloc
