#pragma once
/// Local grids from a short drive (issue 13): sonar firings taken at successive odometry
/// poses, fused into one observation in the frame of the latest pose. Each past firing's
/// sonars are re-mounted at where they were relative to the robot now, so the oriented cone
/// model of every reading is drawn at its own pose and then discretized per candidate
/// heading exactly as for one firing (seed 001 eq. 3; never a built grid turned). Laser scans
/// are fused the same way: each scan's points drawn from where its sensor was.
#include <cstddef>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// One firing of the ring during a drive: the odometry pose it was taken at (any fixed
/// odometry frame: only increments between firings matter), a range per sonar in ring order,
/// and the sonars an echo filter rejected (empty = none).
struct OdometryFiring {
  Pose2 odometry;
  std::vector<double> ranges;
  std::vector<bool> rejected = {};
};

/// Which past firings join the latest one: odometry error grows with the distance and the
/// turn driven, so firings farther back along the path than these bounds are left out. The
/// latest firing is always kept. 2 m: on the drive protocol (gridloc eval --drive 3
/// --drive-firings 7 --drive-window-m W, engine/doc/correlation.md), with odometry off by
/// 2 % + 1 deg/m, 2 m gave the fewest ambiguous and confident wrong answers (1 and 1 in 300;
/// 3 m: 6 confident wrong); with 5 % + 3 deg/m use 1 m (2 m: 25 confident wrong).
struct DriveWindowOptions {
  double max_distance_m = 2.0;               ///< path length from a firing to the latest one (m)
  double max_turn_rad = 1.5707963267948966;  ///< sum of |heading changes| along it (rad)
  std::size_t max_firings = 10;              ///< the latest firing included (>= 1)
};

/// A drive as one observation of a larger, virtual ring: its sonars are the kept firings'
/// sonars re-mounted in the latest pose's frame (oldest firing first, ring order within a
/// firing), its footprint the robot's; `ranges` and `rejected` line up with them. Localize it
/// like one firing: an estimator built with `ring` finds the pose of the latest firing.
struct FusedFirings {
  SonarRing ring;
  std::vector<double> ranges;
  std::vector<bool> rejected;  ///< empty when no firing had rejected sonars
  std::size_t firings = 0;     ///< how many firings were kept
  double distance_m = 0.0;     ///< path length from the oldest kept firing to the latest
  double turn_rad = 0.0;       ///< sum of |heading changes| over that path
};

/// Checks the window's bounds; throws gridloc::Error naming the field.
void validate(const DriveWindowOptions& window);

/// The sonar `spec` of a robot at `relative` (its pose in the current robot frame), as a
/// sonar of the current robot: the same cone in the world, its mount and axis moved by
/// `relative`.
SonarSpec remount(const SonarSpec& spec, const Pose2& relative);

/// Fuses `drive` (firings in time order, the latest last) under `window`. Throws
/// gridloc::Error naming the firing for an empty drive, non-finite odometry or readings that
/// validate_readings() refuses, and naming the field for bad window options.
FusedFirings fuse_firings(const SonarRing& ring, const std::vector<OdometryFiring>& drive,
                          const DriveWindowOptions& window = {});

/// One laser scan during a drive: the robot's odometry pose it was taken at and the scan in
/// the sensor's frame.
struct OdometryScan {
  Pose2 odometry;
  RangeScan scan;
};

/// A drive of scans as one rigid point set in the latest pose's frame (ScanPoints: every
/// scan's beam ends, then every scan's free samples).
struct FusedScans {
  ScanPoints points;
  std::size_t scans = 0;    ///< how many scans were kept
  double distance_m = 0.0;  ///< path length from the oldest kept scan to the latest
  double turn_rad = 0.0;    ///< sum of |heading changes| over that path
};

/// Fuses `drive` (scans in time order, the latest last) under `window`: each kept scan's
/// points are drawn by `model` from where its sensor was, `mount` (the sensor's pose on the
/// robot) composed with the robot's odometry pose relative to the latest. Throws
/// gridloc::Error naming the scan for an empty drive, non-finite odometry or a scan that
/// fails validate(), and naming the field for bad options (the ray model has no points).
FusedScans fuse_scans(const std::vector<OdometryScan>& drive, const Pose2& mount,
                      const ScanModelOptions& model, const DriveWindowOptions& window = {});

}  // namespace gridloc
