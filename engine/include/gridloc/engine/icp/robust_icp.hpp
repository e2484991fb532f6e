#pragma once
/// Robust scan-to-scan ICP (seed 004, "self-localization with an active omni-directional range
/// sensor"): point-to-tangent-line distances, Huber's M-estimator with the scale of the previous
/// iteration's errors, and matching points chosen per segment from its shape complexity C_f.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gridloc/engine/icp/map_contour.hpp"
#include "gridloc/grids/geometry.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// A run of consecutive scan points closer than the gap threshold (seed 004 §3.2), with its
/// total-least-squares line and shape complexity.
struct Segment {
  std::size_t begin = 0;  ///< index of the first point in the scan
  std::size_t end = 0;    ///< one past the last point
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< unit direction of the fitted line
  double mean_distance_m = 0.0;     ///< d_m: mean orthogonal distance of the points to the line
  double complexity = 0.1;          ///< C_f in [0.1, 1]
  std::size_t matching_points = 0;  ///< N_s: matching points drawn from this segment

  std::size_t size() const { return end - begin; }
};

/// How the Huber threshold's scale sigma is taken from the previous iteration's residuals.
enum class HuberScale {
  kMad,     ///< 1.4826 * median(|r|) (robust; the default)
  kStdDev,  ///< standard deviation of the residuals (seed 004's words after eq. (5))
};

/// Options of match_scans(). Defaults follow seed 004 where it gives a value.
struct IcpOptions {
  double gap_m = 0.08;         ///< segmentation gap: seed 004 §3.2, "every points within 8 cm"
  double resolution_m = 0.04;  ///< R_m of eq. (11): seed 004's 40.1 mm per pixel
  /// Segments shorter than this give no matching points. Seed 004 §3.2 says segmentation
  /// "has an effect on noise reduction", which only holds if isolated points are dropped; 3
  /// (not 1) is that reading: a lone spurious return or a pair never steers the match.
  std::size_t min_segment_points = 3;
  /// Grazing angle lambda (rad) of the range-adaptive gap (segment_scan): consecutive points
  /// r apart in range with beam step d still join when within gap_m + r sin(d)/sin(lambda-d)
  /// (at most 4 beam spacings; segment_scan), so a 1 degree laser's walls at 5-10 m stay
  /// whole. 0 keeps the seed's fixed gap.
  double breakpoint_angle_rad = 0.174532925199;  // 10 deg
  /// The reference scan's tangent at a point: the line through this many points of its
  /// segment centred on it; 2 or fewer: the chord to the neighbour that passes closer.
  std::size_t tangent_points = 5;
  bool use_complexity = true;  ///< N_s = ceil(C_f * N_m) per segment; false: every point
  /// With use_complexity, at least this many matching points (or every kept point if fewer):
  /// when the N_s sum to less, each N_s grows by one factor. Seed 004's 720-point scans give
  /// plenty; a 180-beam laser would keep 20.
  std::size_t min_matching_points = 150;
  bool robust = true;      ///< Huber weights; false: plain least squares (weight 1)
  double huber_k = 1.345;  ///< Huber threshold in units of sigma (95 % Gaussian efficiency)
  HuberScale scale = HuberScale::kMad;
  double min_scale_m = 1e-6;  ///< floor of sigma, so noise-free data do not divide by zero
  /// Pairs farther apart than this are not used. 0.5 m covers a prior off by 0.3 m and 10 deg
  /// at a few metres; wider lets real scans slide into wrong alignments (2 m: 21 failures of
  /// 106 Intel pairs, 0.5 m: 11; engine/doc/icp.md, "Real laser data").
  double max_correspondence_m = 0.5;
  int max_iterations = 50;
  /// A matching point "fits" (IcpResult::fitting_pairs) within this point-to-tangent distance.
  double fit_distance_m = 0.1;
  // Seed 004 eq. (12)'s stopping rule (over segments m, iteration k, matching error d_e) is lost
  // in the scanned text; the loop stops when one Gauss-Newton update is below both thresholds.
  double converged_xy_m = 1e-7;       ///< stop when the update moves less than this ...
  double converged_theta_rad = 1e-7;  ///< ... and turns less than this
  /// Also converged when the last 5 poses lie within these of each other: on real scans a
  /// few pairs can flip between two tangents forever, the pose cycling within a tiny region.
  double settled_xy_m = 1e-3;
  double settled_theta_rad = 1e-3;
};

/// What match_scans() found.
struct IcpResult {
  Pose2 pose;  ///< pose of the current scan in the reference scan's frame
  int iterations = 0;
  bool converged = false;
  double rms_m = 0.0;  ///< RMS of the final point-to-tangent residuals (all pairs, outliers too)
  /// Share of the final pairs within huber_k * sigma (Huber weight 1), also when robust = false.
  double inlier_share = 0.0;
  std::size_t pairs = 0;            ///< pairs used in the last iteration
  std::size_t matching_points = 0;  ///< matching points drawn from the current scan
  std::size_t fitting_pairs = 0;    ///< final pairs within IcpOptions::fit_distance_m
  /// Gauss-Newton covariance scale_m^2 H^-1 of (x, y, theta) of `pose` from the inlier pairs;
  /// infinite variances (no correlation) when they leave a direction unconstrained (a
  /// corridor's axis) or are fewer than 3.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double scale_m = 0.0;  ///< sigma used in the last iteration
};

/// Checks options; throws gridloc::Error naming the field.
void validate(const IcpOptions& options);

/// The points of a scan's returns (0 < range < max_range) in its robot frame, in beam order.
std::vector<Eigen::Vector2d> scan_returns(const RangeScan& scan);

/// Splits an ordered scan into runs whose consecutive points are closer than `gap_m`
/// (seed 004 §3.2), fits each a total-least-squares line and sets d_m, C_f and N_s with
/// `resolution_m` = R_m. With `breakpoint_angle_rad` = lambda > 0 the gap grows with range:
/// gap_m + r min(sin(d) / sin(lambda - d), 4 sin(d)), d the scan's median angular step, r the
/// previous point's range; scans with d > lambda / 2 keep the fixed gap (IcpOptions). Throws
/// gridloc::Error if gap_m or resolution_m is not positive or lambda is outside [0, pi/2).
std::vector<Segment> segment_scan(const std::vector<Eigen::Vector2d>& points, double gap_m,
                                  double resolution_m = 0.04, double breakpoint_angle_rad = 0.0);

/// Seed 004 eq. (11): C_f = min(1, (d_m + R_m) / (10 R_m)); 0.1 for a straight segment.
double shape_complexity(double mean_distance_m, double resolution_m);

/// Seed 004 eq. (12) as read here: N_s = ceil(C_f * N_m), at least 1 for a non-empty segment.
std::size_t matching_point_count(double complexity, std::size_t segment_size);

/// Huber's weight (seed 004 eq. (6)): 1 for |r| <= k, k / |r| beyond.
double huber_weight(double r, double k);

/// The scale sigma of residuals `r` by `rule` (MAD: 1.4826 * median |r|), floored at `floor_m`.
double residual_scale(const std::vector<double>& r, HuberScale rule, double floor_m);

/// Finds the pose of `current` in `reference`'s frame by robust point-to-tangent-line ICP
/// starting from `initial`. Both scans are ordered (by bearing) 2-D points in metres, each in
/// its own robot frame. Throws gridloc::Error on empty / too small / non-finite input or bad
/// options.
IcpResult match_scans(const std::vector<Eigen::Vector2d>& reference,
                      const std::vector<Eigen::Vector2d>& current, const Pose2& initial = {},
                      const IcpOptions& options = {});

/// Scan-to-map ICP: the pose (world frame) of `scan` (robot-frame points in beam order)
/// against the map's contour points and their normals, from `initial`; the same matching
/// points, weights and stopping rules as match_scans(). Throws gridloc::Error as match_scans()
/// and for a contour of fewer than 3 points.
IcpResult match_scan_to_map(const MapContour& contour, const std::vector<Eigen::Vector2d>& scan,
                            const Pose2& initial, const IcpOptions& options = {});

}  // namespace gridloc
