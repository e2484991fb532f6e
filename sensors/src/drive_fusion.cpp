// Local grids from a short drive: past firings re-mounted in the latest pose's frame.
#include "gridloc/sensors/drive_fusion.hpp"

#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const DriveWindowOptions& window) {
  if (!(window.max_distance_m >= 0.0) || !std::isfinite(window.max_distance_m)) {
    throw Error("drive window: max_distance_m must be finite and >= 0, got " +
                std::to_string(window.max_distance_m));
  }
  if (!(window.max_turn_rad >= 0.0) || !std::isfinite(window.max_turn_rad)) {
    throw Error("drive window: max_turn_rad must be finite and >= 0, got " +
                std::to_string(window.max_turn_rad));
  }
  if (window.max_firings < 1) throw Error("drive window: max_firings must be at least 1");
}

namespace {

/// Throws unless every firing has finite odometry and readings the ring accepts.
void check_drive(const SonarRing& ring, const std::vector<OdometryFiring>& drive) {
  if (drive.empty()) throw Error("drive: no firing to fuse (the latest firing is needed)");
  for (std::size_t k = 0; k < drive.size(); ++k) {
    const Pose2& pose = drive[k].odometry;
    const std::string where = "drive: firing " + std::to_string(k) + ": ";
    if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
      throw Error(where + "odometry pose is not finite");
    }
    try {
      validate_readings(ring, drive[k].ranges, drive[k].rejected);
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
  }
}

/// The index of the oldest firing the window keeps, with the path's length and turn from it
/// to the latest firing.
struct KeptSpan {
  std::size_t first = 0;
  double distance_m = 0.0;
  double turn_rad = 0.0;
};

/// Walks back from the latest reading (a firing or a scan) while the path stays within the
/// window's bounds.
template <class Reading>
KeptSpan kept_span(const std::vector<Reading>& drive, const DriveWindowOptions& window) {
  KeptSpan span{drive.size() - 1, 0.0, 0.0};
  while (span.first > 0 && drive.size() - span.first < window.max_firings) {
    const Pose2& older = drive[span.first - 1].odometry;
    const Pose2& newer = drive[span.first].odometry;
    const double distance = span.distance_m + std::hypot(newer.x - older.x, newer.y - older.y);
    const double turn = span.turn_rad + std::abs(normalize_angle(newer.theta - older.theta));
    if (distance > window.max_distance_m || turn > window.max_turn_rad) break;
    span = {span.first - 1, distance, turn};
  }
  return span;
}

/// Whether any kept firing carries a rejection mask.
bool any_rejected(const std::vector<OdometryFiring>& drive, std::size_t first) {
  for (std::size_t k = first; k < drive.size(); ++k) {
    if (!drive[k].rejected.empty()) return true;
  }
  return false;
}

}  // namespace

SonarSpec remount(const SonarSpec& spec, const Pose2& relative) {
  const double c = std::cos(relative.theta), s = std::sin(relative.theta);
  const double mount_x = spec.radius * std::cos(spec.bearing);
  const double mount_y = spec.radius * std::sin(spec.bearing);
  const double x = relative.x + c * mount_x - s * mount_y;
  const double y = relative.y + s * mount_x + c * mount_y;
  SonarSpec moved = spec;
  moved.radius = std::hypot(x, y);
  moved.bearing = moved.radius > 0.0 ? std::atan2(y, x) : 0.0;
  moved.heading = normalize_angle(spec.heading + relative.theta);
  return moved;
}

FusedFirings fuse_firings(const SonarRing& ring, const std::vector<OdometryFiring>& drive,
                          const DriveWindowOptions& window) {
  validate(window);
  check_drive(ring, drive);
  const KeptSpan span = kept_span(drive, window);
  const Pose2& latest = drive.back().odometry;
  const bool with_rejected = any_rejected(drive, span.first);

  FusedFirings fused;
  fused.ring.name = ring.name + " (" + std::to_string(drive.size() - span.first) + " firings)";
  fused.ring.footprint = ring.footprint;
  for (std::size_t k = span.first; k < drive.size(); ++k) {
    const Pose2 relative = relative_pose(latest, drive[k].odometry);
    for (std::size_t i = 0; i < ring.sonars.size(); ++i) {
      fused.ring.sonars.push_back(remount(ring.sonars[i], relative));
      fused.ranges.push_back(drive[k].ranges[i]);
      if (with_rejected)
        fused.rejected.push_back(!drive[k].rejected.empty() && drive[k].rejected[i]);
    }
  }
  fused.firings = drive.size() - span.first;
  fused.distance_m = span.distance_m;
  fused.turn_rad = span.turn_rad;
  return fused;
}

namespace {

/// Throws unless every scan has finite odometry and passes validate().
void check_scans(const std::vector<OdometryScan>& drive) {
  if (drive.empty()) throw Error("drive: no scan to fuse (the latest scan is needed)");
  for (std::size_t k = 0; k < drive.size(); ++k) {
    const Pose2& pose = drive[k].odometry;
    const std::string where = "drive: scan " + std::to_string(k) + ": ";
    if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
      throw Error(where + "odometry pose is not finite");
    }
    try {
      validate(drive[k].scan);
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
  }
}

}  // namespace

FusedScans fuse_scans(const std::vector<OdometryScan>& drive, const Pose2& mount,
                      const ScanModelOptions& model, const DriveWindowOptions& window) {
  validate(window);
  check_scans(drive);
  const KeptSpan span = kept_span(drive, window);
  const Pose2& latest = drive.back().odometry;
  std::vector<ScanPoints> parts;
  for (std::size_t k = span.first; k < drive.size(); ++k) {
    const Pose2 sensor = compose(relative_pose(latest, drive[k].odometry), mount);
    parts.push_back(scan_points(drive[k].scan, model, sensor));
  }
  FusedScans fused;
  fused.points = merge_points(parts);
  fused.scans = drive.size() - span.first;
  fused.distance_m = span.distance_m;
  fused.turn_rad = span.turn_rad;
  return fused;
}

}  // namespace gridloc
