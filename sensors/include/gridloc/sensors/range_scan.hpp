#pragma once
/// Laser and rotating-IR scans as observations: each beam's end cell is occupied, the cells
/// the beam crossed before it are free, so the same correlation search serves a 360-beam
/// laser as well as the sonar ring.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/limits.hpp"
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
/// of ../shared/bench-cases. Throws gridloc::Error naming the file and line; also for a
/// missing file, a directory or device, a file over limits.max_file_mb, a line over 64 KiB
/// and a scan of more than limits.max_beams beams (checked line by line: reading stops at the
/// first beam over the limit).
RangeScan load_scan_csv(const std::string& path, double max_range,
                        const ResourceLimits& limits = {});

/// Which cells of a beam the local grid marks. Every model marks a beam's end cell +1 (a cell
/// hit by several beams stays +1; end cells beat free cells); Rays and Samples also give the
/// free part of a beam a total of -1 (free values of several beams add), a beam without
/// return being free up to the max range.
enum class ScanModel {
  /// The n cells a beam crosses before its end, -1/n each: the complete ray model.
  Rays,
  /// `free_samples` points evenly spaced along the beam, -1/free_samples each: far fewer
  /// cells (a 360-beam 8 m scan at 5 cm: ~1.8 k instead of ~24 k), and the points move
  /// rigidly with the robot, which lets branch and bound bound whole heading intervals.
  Samples,
  /// End cells only (the "hits" model of real-time correlative matchers).
  Hits,
};

struct ScanModelOptions {
  /// Hits by default: on the apartment peer case it is as accurate as Samples and 3-5x faster
  /// (bench/RESULTS.md); Samples adds evidence from free space.
  ScanModel model = ScanModel::Hits;
  int free_samples = 4;  ///< per beam, for ScanModel::Samples (>= 1)
};

/// The model's name, as the command line and benchmarks spell it: "rays", "samples", "hits".
std::string to_string(ScanModel model);

/// Checks options; throws gridloc::Error naming the field.
void validate(const ScanModelOptions& options);

/// A scan as weighted points rigidly attached to the robot (ScanModel::Samples and Hits): the
/// local grid at any heading is these points rotated and rounded to cells (rasterize_points).
/// Points [0, hit_count) are beam ends (weight +1), the rest free samples (weight < 0).
struct ScanPoints {
  std::vector<double> x;  ///< robot frame (m)
  std::vector<double> y;
  std::vector<double> norm;  ///< distance from the robot centre (m)
  std::vector<float> weight;
  std::size_t hit_count = 0;
  double max_norm = 0.0;  ///< the largest distance of a point from the robot centre (m)
  std::size_t size() const { return weight.size(); }
};

/// The points of `scan` under `options` (model Samples or Hits; throws gridloc::Error for
/// Rays), for a sensor at `mount` (its pose in the robot frame; an off-centre laser, or a
/// past scan of a drive placed in the latest pose's frame). The scan must have passed
/// validate().
ScanPoints scan_points(const RangeScan& scan, const ScanModelOptions& options,
                       const Pose2& mount = {});

/// The points of several scans as one rigid set (a drive fused in one frame): every part's
/// beam ends first, then every part's free samples, so hit_count still splits them.
ScanPoints merge_points(const std::vector<ScanPoints>& parts);

/// floor(v) for |v| < 2^31, exactly, without a libm call (x86-64's baseline has no SSE4.1
/// rounding instruction).
inline int floor_to_int(double v) {
  const int i = static_cast<int>(v);
  return i - (static_cast<double>(i) > v);
}

/// Point k for heading (cos_t, sin_t), in cells (`inv_res` cells per metre) from the robot
/// centre. Rotating the heading by dtheta moves it by at most |p| * |dtheta| * inv_res.
inline Eigen::Vector2d point_position(const ScanPoints& p, std::size_t k, double cos_t,
                                      double sin_t, double inv_res) {
  return {(cos_t * p.x[k] - sin_t * p.y[k]) * inv_res, (sin_t * p.x[k] + cos_t * p.y[k]) * inv_res};
}

/// The cell (from the robot's cell) of point k, the robot centre lying (cx, cy) cells from
/// its cell's centre: the one rounding rule rasterize_points, place_points and the
/// heading-interval bounds of branch and bound share.
inline Eigen::Vector2i point_cell(const ScanPoints& p, std::size_t k, double cos_t, double sin_t,
                                  double inv_res, double cx = 0.0, double cy = 0.0) {
  const Eigen::Vector2d u = point_position(p, k, cos_t, sin_t, inv_res);
  return {floor_to_int(u.x() + cx + 0.5), floor_to_int(u.y() + cy + 0.5)};
}

/// The local grid of `points` for heading `theta`: a cell holding a beam end is +1, any other
/// cell the sum of its free samples' weights. Same conventions as rasterize_scan.
SparseLocalGrid rasterize_points(const ScanPoints& points, double theta, double resolution,
                                 const Eigen::Vector2d& centre = Eigen::Vector2d::Zero());

/// The local grid of a scan for robot heading `theta` (rad), cells of `resolution` (m), robot
/// centre `centre` (m) from the centre of cell (0, 0), under `options` (see ScanModel). The
/// scan must have passed validate().
SparseLocalGrid rasterize_scan(const RangeScan& scan, double theta, double resolution,
                               const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                               const ScanModelOptions& options = {});

}  // namespace gridloc
