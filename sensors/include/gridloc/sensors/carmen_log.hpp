#pragma once
/// CARMEN robot logs (the format of the public SLAM datasets): laser scans and odometry with
/// their timestamps, read from `FLASER`, `ROBOTLASER1` and `ODOM` lines. Other lines
/// (`PARAM`, `SYNC`, `NEFF`, ...) and `#` comments are skipped.
#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

struct CarmenOptions {
  /// FLASER lines carry no maximum range: ranges at or beyond this (m) are "no return" (SICK
  /// scanners report about 81.9 m for no echo).
  double max_range = 80.0;
  /// load_carmen_log reads at most this many bytes of log text (after decompression, for a
  /// gzip file), so a bad file cannot fill the memory: 2 GiB, 200 times the largest log of
  /// ../shared/datasets (freiburg-079, 9.5 MB).
  std::size_t max_decompressed_bytes = std::size_t{2} << 30;
  /// The file (max_file_mb, compressed size for a gzip), each line's reading and remission
  /// counts (max_beams) and the records read so far (max_memory_mb: 16 bytes a beam plus
  /// each record) are checked against these while reading: a bad log stops where it goes over.
  ResourceLimits limits;
};

/// One laser scan of the log.
struct LaserRecord {
  double timestamp = 0.0;  ///< the line's first timestamp (ipc_timestamp), s
  /// The unit of the timestamp's last printed digit (logs print 6 significant digits:
  /// "1777.35" is known to 0.01 s), for matching times.
  double timestamp_resolution = 0.0;
  RangeScan scan;          ///< angles in the laser's frame (rad), ranges (m)
  Pose2 laser_pose;        ///< FLASER: the logged pose (the corrected one in SLAM-corrected logs)
  Pose2 robot_pose;        ///< FLASER: the second logged pose; ROBOTLASER1: the robot's pose
  std::size_t line = 0;    ///< 1-based line number in the file
  int invalid_ranges = 0;  ///< NaN or infinite readings, kept as no return (max range)
};

struct OdometryRecord {
  double timestamp = 0.0;
  Pose2 pose;
  double tv = 0.0;  ///< translational velocity, m/s
  double rv = 0.0;  ///< rotational velocity, rad/s
  std::size_t line = 0;
};

struct CarmenLog {
  std::vector<LaserRecord> lasers;
  std::vector<OdometryRecord> odometry;
};

/// Parses a CARMEN log from `in`; `name` names it in errors. Throws gridloc::Error naming the
/// line and field for a malformed FLASER / ROBOTLASER1 / ODOM line (too few fields, a field
/// that is not a number, a reading count that does not match, a negative range), a reading
/// count over options.limits.max_beams, a line longer than such a scan needs, or records
/// over options.limits.max_memory_mb. A NaN or
/// infinite range, which real logs use for an invalid beam, reads as no return (counted in
/// LaserRecord::invalid_ranges).
///
/// FLASER `n r1..rn x y th odom_x odom_y odom_th ipc_timestamp host logger_timestamp`: n ranges
/// over the laser's 180 degree front field, from -90 degrees; odd n includes both ends (181:
/// 1 degree apart, 361: 0.5), even n does not (180: 1 degree). ROBOTLASER1 gives its start
/// angle, field of view, resolution and maximum range itself.
CarmenLog parse_carmen_log(std::istream& in, const std::string& name,
                           const CarmenOptions& options = {});

/// parse_carmen_log of a file, plain or gzip-compressed (`.log.gz`, recognised by its content,
/// not its name). Throws gridloc::Error naming the file when it is missing or unreadable, a
/// directory or device, over options.limits.max_file_mb, when its gzip data are corrupt or
/// truncated, or when it holds more than
/// options.max_decompressed_bytes of text.
CarmenLog load_carmen_log(const std::string& path, const CarmenOptions& options = {});

}  // namespace gridloc
