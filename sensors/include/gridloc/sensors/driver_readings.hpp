#pragma once
/// Sonar readings as drivers publish them (ROS REP 117, sensor_msgs/Range), turned into the
/// ranges and rejection mask the local grid reads.
#include <vector>

#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

struct DriverReadings {
  std::vector<double> ranges;  ///< one per sonar, within [min_range, max_range]
  std::vector<bool> rejected;  ///< sonars that said "too close": they draw no cone
};

/// Converts one firing of raw driver values (one per sonar, in ring order):
/// - +inf, or a value above max_range by at most `max_range_slack_m`: no echo (max_range);
/// - -inf, or a value below min_range: an obstacle too close to range; the sonar draws no
///   cone (neither arc nor free sector) and counts as rejected;
/// - NaN, a negative value, or a value beyond max_range + slack: gridloc::Error naming the
///   sonar and the value. A firing whose every sonar was too close is an error as well.
DriverReadings from_driver(const SonarRing& ring, const std::vector<double>& raw,
                           double max_range_slack_m = 0.01);

}  // namespace gridloc
