#pragma once
// Shared by the tracking tests: a 360-degree laser of 6 m range on the two-rooms map, the
// laser Localizer's options at 5 cm, and what counts as right (10 cm, 2 degrees).
#include <cmath>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/sensors/scan_sim.hpp"

namespace gridloc::test {

inline constexpr double kRange = 6.0;

inline RangeScan scan_at(const OccupancyMap& map, const Pose2& pose) {
  return simulate_scan(map, pose, 360, kRange, 0.0, 1);
}

inline LocalizerOptions laser_options() {
  LocalizerOptions options;
  options.correlation.resolution = 0.05;
  return options;
}

inline LaserSensor laser() {
  LaserSensor sensor;
  sensor.max_range = kRange;
  return sensor;
}

inline bool right(const Estimate& e, const Pose2& truth) {
  return std::hypot(e.pose.x - truth.x, e.pose.y - truth.y) <= 0.1 &&
         std::abs(normalize_angle(e.pose.theta - truth.theta)) <= deg2rad(2.0);
}

}  // namespace gridloc::test
