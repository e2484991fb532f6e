#pragma once
/// The raw odometry in a GMapping output file (issue 34: real odometry besides simulated
/// errors). A `.gfs` file (e.g. the shared csail.corrected.gfs) logs each laser scan the SLAM
/// used as `LASER_READING n r1..rn x y theta timestamp`, the pose being the robot's raw
/// odometry; its SLAM-corrected twin log has the same scans in the same order.
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/sensors/carmen_log.hpp"

namespace gridloc {

struct GfsScan {
  std::vector<double> ranges;
  Pose2 odometry;  ///< the raw odometry pose at the scan
  double timestamp = 0.0;
  std::size_t line = 0;  ///< 1-based
};

/// Reads every LASER_READING line of a .gfs file (other lines are skipped). Throws
/// gridloc::Error naming the file and line for a malformed one, the file for one over
/// limits.max_file_mb or without a LASER_READING line.
std::vector<GfsScan> load_gfs_scans(const std::string& path, const ResourceLimits& limits = {});

/// The raw odometry of each of `log`'s laser scans, from `gfs` (its scans in the same order):
/// the counts must agree and each pair's ranges must match (within 1 cm, at most 2 % of the
/// beams off), or gridloc::Error names the first scan that does not.
std::vector<Pose2> scan_odometry_from_gfs(const CarmenLog& log, const std::vector<GfsScan>& gfs);

}  // namespace gridloc
