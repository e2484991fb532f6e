#pragma once
/// The Localizer: the facade a navigation stack links (issue 13). Built once from a map and
/// the sonar ring, it is fed odometry and sonar firings as the robot drives and keeps the
/// current Estimate: each firing is fused with the drive behind it (fuse_firings) and matched
/// by the exact correlation search, globally until a fix, then in a window around the fix
/// carried along by odometry.
#include <Eigen/Core>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/sensors/drive_fusion.hpp"

namespace gridloc {

struct LocalizerOptions {
  /// The search; its reach_m is raised to cover the ring along the whole drive window.
  CorrelationOptions correlation;
  /// Which past firings join the latest (distance, turn, count).
  DriveWindowOptions drive;
  /// The window around a prior spans this many standard deviations of its covariance...
  double prior_sigmas = 3.0;
  /// ...grown by the odometry's error since the prior: this share of the distance driven...
  double odometry_error_per_m = 0.02;
  /// ...and this heading error per metre driven (rad/m; 1 deg/m).
  double odometry_turn_error_per_m = 0.017453292519943295;
  double min_half_xy_m = 0.3;    ///< the window's half side is at least this...
  double max_half_xy_m = 2.0;    ///< ...and at most this (beyond: localize globally)
  double min_half_theta = 0.17;  ///< rad (10 deg): the half heading range is at least this
  /// After this many firings in a row that were not `localized`, the prior is dropped and
  /// the next firing searches the whole map (a wrong prior or a lost track).
  int misses_before_global = 3;
  /// Driver values up to this far above a sonar's max range read as no echo (from_driver).
  double max_range_slack_m = 0.01;
};

/// What the Localizer holds between calls (see Localizer).
struct LocalizerState {
  std::optional<Pose2> odometry;      ///< the latest odometry pose
  std::vector<OdometryFiring> drive;  ///< firings within the drive window, oldest first
  std::optional<Pose2> prior;         ///< the pose believed at `prior_odometry`, world frame
  Eigen::Matrix3d prior_covariance = Eigen::Matrix3d::Zero();
  Pose2 prior_odometry;              ///< the odometry pose the prior was given at
  double travelled_m = 0.0;          ///< odometry path length since the prior
  int misses = 0;                    ///< firings in a row that were not `localized`
  std::optional<Estimate> estimate;  ///< the latest firing's estimate
};

/// Thread safety: one writer (reset, set_prior, add_observation) and any number of readers
/// (estimate) at the same time; add_odometry may come from another thread too, also while a
/// firing is being localized (the firing keeps the odometry it was taken at). Readers get the
/// previous estimate while a firing is being localized. The answer does not depend on
/// CorrelationOptions::threads.
class Localizer {
 public:
  /// Precomputes the global grids once; throws gridloc::Error for a bad map, ring or options.
  Localizer(OccupancyMap map, SonarRing ring, LocalizerOptions options = {});

  /// Forgets the drive, the prior and the estimate (not the latest odometry pose): the next
  /// firing localizes globally.
  void reset();
  /// The robot is at `pose` (world frame) with `covariance` of (x, y, theta) now, at the
  /// latest odometry pose. Throws for a non-finite pose or covariance, or a negative
  /// variance.
  void set_prior(const Pose2& pose, const Eigen::Matrix3d& covariance);
  /// The robot's odometry pose now (any fixed odometry frame); firings are taken here. The
  /// path length since the prior grows the search window.
  void add_odometry(const Pose2& odometry);
  /// A firing of the ring at the latest odometry pose (the odometry origin when none was
  /// given), as the driver publishes it (from_driver: +inf no echo, -inf too close); fuses it
  /// with the drive and localizes. A `localized` answer becomes the prior of the next firing;
  /// after LocalizerOptions::misses_before_global answers that are not, or when the carried
  /// prior leaves the map, the search is global again.
  /// `time_s` must be finite; this version does not use it otherwise. Throws gridloc::Error
  /// for bad readings (the state is then unchanged).
  void add_observation(double time_s, const std::vector<double>& driver_ranges);
  /// The latest firing's estimate (pose, covariance, verdict, hypotheses); gridloc::Error
  /// before the first firing.
  Estimate estimate() const;

  const CorrelationEstimator& estimator() const { return estimator_; }

 private:
  SearchWindow window_now(const LocalizerState& state) const;

  LocalizerOptions options_;
  CorrelationEstimator estimator_;
  mutable std::shared_mutex mutex_;
  LocalizerState state_;
};

}  // namespace gridloc
