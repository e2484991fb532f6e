#pragma once
// A small CARMEN log for the CLI tests: FLASER lines simulated in a walled room.
#include <sstream>
#include <string>

#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc::test {

/// A 6 m x 4 m room at 5 cm, origin (0, 0).
inline OccupancyMap flaser_room() {
  return walled_room(120, 80, 0.05, {0.0, 0.0});
}

/// `scans` FLASER lines (181 readings over the front 180 degrees) in flaser_room(), driving
/// east then turning, `dt` seconds apart from t = 5.
inline std::string flaser_log(int scans, double dt) {
  const OccupancyMap room = flaser_room();
  std::ostringstream out;
  out.precision(9);
  for (int k = 0; k < scans; ++k) {
    const Pose2 pose{1.0 + 4.0 * k / scans, 2.0, 0.15 * k};
    const RangeScan all = simulate_scan(room, pose, 360, 8.0, 0.005, k + 1);
    out << "FLASER 181";
    for (int b = 90; b <= 270; ++b) out << " " << (all.ranges[b] < 8.0 ? all.ranges[b] : 81.91);
    for (int twice = 0; twice < 2; ++twice)
      out << " " << pose.x << " " << pose.y << " " << pose.theta;
    out << " " << 5.0 + dt * k << " sim " << 5.0 + dt * k << "\n";
  }
  return out.str();
}

}  // namespace gridloc::test
