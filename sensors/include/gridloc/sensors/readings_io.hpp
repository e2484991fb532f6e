#pragma once
/// Readings files: JSON `{"ranges_m": [d0, d1, ...]}` (what `gridloc simulate` writes; other
/// keys are ignored), one range per sonar in ring order, max_range meaning no echo.
#include <string>
#include <vector>

namespace gridloc {

/// Loads the ranges of a readings file; throws gridloc::Error for a missing or malformed file.
/// The values are checked against a ring by validate_readings().
std::vector<double> load_readings(const std::string& path);

}  // namespace gridloc
