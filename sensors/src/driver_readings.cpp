// Sonar readings as drivers publish them (REP 117): +inf, -inf, too close, a hair too far.
#include "gridloc/sensors/driver_readings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

[[noreturn]] void refuse(std::size_t sonar, double value, const char* why) {
  std::ostringstream message;
  message << "driver readings: sonar " << sonar << " = " << value << " " << why;
  throw Error(message.str());
}

}  // namespace

DriverReadings from_driver(const SonarRing& ring, const std::vector<double>& raw,
                           double max_range_slack_m) {
  if (!(max_range_slack_m >= 0.0) || !std::isfinite(max_range_slack_m)) {
    throw Error("driver readings: the max range slack must be finite and >= 0, got " +
                std::to_string(max_range_slack_m));
  }
  if (raw.size() != ring.sonars.size()) {
    throw Error("driver readings: expected " + std::to_string(ring.sonars.size()) +
                " values (one per sonar of ring '" + ring.name + "'), got " +
                std::to_string(raw.size()));
  }
  DriverReadings readings{std::vector<double>(raw.size()), std::vector<bool>(raw.size(), false)};
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const SonarSpec& sonar = ring.sonars[i];
    const double value = raw[i];
    if (std::isnan(value)) refuse(i, value, "is NaN (an erroneous reading)");
    if (value == -std::numeric_limits<double>::infinity() ||
        (value >= 0.0 && value < sonar.min_range)) {
      readings.ranges[i] = sonar.min_range;
      readings.rejected[i] = true;
    } else if (value < 0.0) {
      refuse(i, value, "is negative");
    } else if (value > sonar.max_range + max_range_slack_m && std::isfinite(value)) {
      std::ostringstream why;
      why << "is beyond the sonar's max range " << sonar.max_range << " m by more than "
          << max_range_slack_m << " m (+inf means no echo)";
      refuse(i, value, why.str().c_str());
    } else {
      readings.ranges[i] = std::min(value, sonar.max_range);
    }
  }
  if (std::all_of(readings.rejected.begin(), readings.rejected.end(), [](bool r) { return r; })) {
    throw Error("driver readings: every sonar reported an obstacle too close to range");
  }
  return readings;
}

}  // namespace gridloc
