#pragma once
/// Running the Localizer through a CARMEN log (issue 13, `gridloc track`): each laser scan's
/// odometry goes to add_odometry, every `every`-th scan to add_observation, and each
/// processed scan's Estimate comes back with the path driven, the time it took and, when the
/// log's poses are SLAM-corrected, its error against them.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "gridloc/engine/evaluation/shard.hpp"
#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/sensors/carmen_log.hpp"
#include "gridloc/sensors/odometry_noise.hpp"

namespace gridloc {

/// Where the odometry comes from: the laser lines' robot pose fields (FLASER odom_x, odom_y,
/// odom_theta; ROBOTLASER1's robot pose) or the ODOM lines, taken at each scan's time.
enum class OdometrySource { Laser, Odom };

/// "laser" or "odom".
std::string to_string(OdometrySource source);
/// The source to_string() names; gridloc::Error listing the choices otherwise.
OdometrySource parse_odometry_source(const std::string& name);

struct LogTrackingOptions {
  LocalizerOptions localizer;
  LaserSensor laser;  ///< its mount is the laser's pose on the robot (identity: at the centre)
  OdometrySource odometry = OdometrySource::Laser;
  /// The robot's own odometry at each of the log's scans (e.g. scan_odometry_from_gfs);
  /// non-empty: used instead of `odometry` (the log's poses stay the truth).
  std::vector<Pose2> raw_odometry;
  /// Seeded systematic error added to the odometry (for logs whose poses are corrected);
  /// unset: the odometry as logged.
  std::optional<OdometryNoise> odometry_noise;
  std::uint64_t seed = 1;
  /// The pose at the first processed scan and its covariance; unset: localize globally.
  std::optional<Pose2> prior;
  Eigen::Matrix3d prior_covariance = Eigen::Vector3d(0.01, 0.01, 0.0076).asDiagonal();
  int every = 1;  ///< process every `every`-th scan of `scans` (>= 1)
  /// The scans (indices into the log's lasers, increasing) to run through; empty: all.
  /// Odometry is fed at every one of them, observations at every `every`-th.
  std::vector<std::size_t> scans;
  /// Stop after the first processed scan at which the odometry path reaches this (m); 0: run
  /// to the last scan.
  double max_travel_m = 0.0;
};

/// One processed scan.
struct TrackStep {
  std::size_t index = 0;  ///< into the log's lasers
  double time = 0.0;      ///< the scan's timestamp (s)
  Estimate estimate;
  double travelled_m = 0.0;  ///< odometry path length since the first scan run through
  Pose2 odometry;            ///< the odometry pose the Localizer was given at this scan
  double timing_ms = 0.0;    ///< add_observation's wall time
  LocalizerStatus status;    ///< a re-search's progress, a rejected jump
  /// Against the log's pose (the corrected one in SLAM-corrected logs): position error (m)
  /// and heading error (degrees).
  double error_m = 0.0;
  double error_deg = 0.0;
};

/// Checks the options against `log`; throws gridloc::Error naming what is wrong (every < 1,
/// scan indices outside the log or not increasing, ODOM odometry without ODOM lines or
/// without usable timestamps, bad noise or prior).
void validate(const LogTrackingOptions& options, const CarmenLog& log);

/// Runs a Localizer built on `map` through `log` under `options`, calling `on_step` after
/// each processed scan, in order (to print as it goes). Throws gridloc::Error for bad options
/// (validate), a bad map or a scan the Localizer refuses (naming the scan's line).
void track_log(const CarmenLog& log, const OccupancyMap& map, const LogTrackingOptions& options,
               const std::function<void(const TrackStep&)>& on_step);

/// The same with a Localizer built once (for many runs on one map): it is reset() first,
/// and options.localizer and options.laser are not used (the Localizer has its own).
void track_log(const CarmenLog& log, Localizer& localizer, const LogTrackingOptions& options,
               const std::function<void(const TrackStep&)>& on_step);

/// Global localization on a log from a standstill and from a short drive (issue 13): each
/// trial starts at a scan drawn from the candidates, localizes globally, and drives on
/// through the later candidates until the odometry path reaches drive_m.
struct GlobalTrialOptions {
  int trials = 20;
  double drive_m = 5.0;
  std::uint64_t seed = 1;   ///< draws the starts; trial t's odometry noise has seed + t
  double success_m = 0.10;  ///< an answer within these of the log's pose is right (laser)
  double success_deg = 2.0;
  Shard shard;  ///< runs only this shard's trials (every trial's start and seed unchanged)
};

struct GlobalTrial {
  int trial = 0;  ///< its number among options.trials (0-based)
  std::size_t start = 0;
  TrackStep standstill;                     ///< the first scan's answer
  TrackStep end;                            ///< the answer at the end of the drive
  std::optional<double> localized_after_m;  ///< the path driven at the first `localized`
  int wrong_localized = 0;                  ///< `localized` answers beyond success_m / success_deg
};

/// Whether `step` is `localized` within the options' tolerances.
bool right(const TrackStep& step, const GlobalTrialOptions& options);

/// Runs options.trials trials (starts drawn uniformly from `candidates`, the increasing scan
/// indices a trial may use, e.g. a log's held-out part) with `tracking`'s odometry and noise
/// (its prior is ignored: global), calling `on_trial` after each, in order. With a shard,
/// only its trials run, each as in the whole run. Throws gridloc::Error for bad options or
/// no candidates.
void run_global_trials(const CarmenLog& log, Localizer& localizer,
                       const LogTrackingOptions& tracking,
                       const std::vector<std::size_t>& candidates,
                       const GlobalTrialOptions& options,
                       const std::function<void(const GlobalTrial&)>& on_trial);

}  // namespace gridloc
