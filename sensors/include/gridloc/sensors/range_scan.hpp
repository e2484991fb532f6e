#pragma once
/// Laser and rotating-IR scans as observations: each beam's end cell is occupied, the cells
/// the beam crossed before it are free, so the same correlation search serves a 360-beam
/// laser as well as the sonar ring.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/sensors/local_grid.hpp"

namespace gridloc {

/// One scan in the robot frame (sensor at the robot centre): beam k points at angles[k]
/// (rad, CCW from the robot's forward axis) and measured ranges[k] (m); a range >= max_range
/// means no return.
struct RangeScan {
  std::vector<double> angles;
  std::vector<double> ranges;
  double max_range = 8.0;
};

/// Checks a scan; throws gridloc::Error for an empty scan, sizes that differ, non-finite
/// angles, NaN or negative ranges, a non-positive max range, or a scan with no return at all.
void validate(const RangeScan& scan);

/// Reads `angle_rad,range_m` lines (`#` starts a comment; blank lines are skipped), the format
/// of ../shared/bench-cases. Throws gridloc::Error naming the file and line.
RangeScan load_scan_csv(const std::string& path, double max_range);

/// The local grid of a scan for robot heading `theta` (rad), cells of `resolution` (m), robot
/// centre `centre` (m) from the centre of cell (0, 0). Each beam: its end cell +1 (a cell hit
/// by several beams stays +1) and the n cells it crossed before it -1/n each (free values of
/// several beams add); a beam without return crosses max_range of free cells. End cells beat
/// free cells. The scan must have passed validate().
SparseLocalGrid rasterize_scan(const RangeScan& scan, double theta, double resolution,
                               const Eigen::Vector2d& centre = Eigen::Vector2d::Zero());

}  // namespace gridloc
