#pragma once
/// Readings files: JSON `{"ranges_m": [d0, d1, ...]}` (what `gridloc simulate` writes; other
/// keys are ignored), one range per sonar in ring order, max_range meaning no echo; or
/// `{"firings_m": [[d0, d1, ...], ...]}`, several consecutive firings of the ring from one
/// pose (`gridloc simulate --firings K`), for the echo filter (filter_echoes).
#include <string>
#include <vector>

#include "gridloc/grids/limits.hpp"

namespace gridloc {

/// Loads the ranges of a readings file; throws gridloc::Error for a missing or malformed file,
/// a directory or device, a file over limits.max_file_mb, or one holding more than
/// limits.max_beams JSON values in all (counted while parsing: the parse stops there). The
/// values are checked against a ring by validate_readings().
std::vector<double> load_readings(const std::string& path, const ResourceLimits& limits = {});

/// Loads every firing of a readings file: the `firings_m` arrays, or `ranges_m` as a single
/// firing. Throws gridloc::Error as load_readings does, and for a file with neither key.
std::vector<std::vector<double>> load_firings(const std::string& path,
                                              const ResourceLimits& limits = {});

}  // namespace gridloc
