// The Localizer run through a CARMEN log: odometry at every scan, observations at every N-th.
#include "gridloc/engine/evaluation/log_tracking.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

std::string to_string(OdometrySource source) {
  return source == OdometrySource::Laser ? "laser" : "odom";
}

OdometrySource parse_odometry_source(const std::string& name) {
  if (name == "laser") return OdometrySource::Laser;
  if (name == "odom") return OdometrySource::Odom;
  throw Error("odometry source '" + name +
              "': choose laser (the laser lines' pose fields) or odom");
}

namespace {

/// The scans to run through: the given ones, or every scan of the log.
std::vector<std::size_t> selected_scans(const LogTrackingOptions& options, const CarmenLog& log) {
  if (!options.scans.empty()) return options.scans;
  std::vector<std::size_t> all(log.lasers.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  return all;
}

/// Throws unless the log's ODOM lines can give the odometry at the scans' times.
void check_odom_lines(const CarmenLog& log) {
  if (log.odometry.size() < 2) throw Error("--odometry odom: the log has fewer than 2 ODOM lines");
  const double first = log.odometry.front().timestamp, last = log.odometry.back().timestamp;
  if (!(last > first)) {
    throw Error("--odometry odom: the ODOM lines' timestamps do not increase (they span " +
                std::to_string(first) + " to " + std::to_string(last) + " s)");
  }
}

/// The ODOM pose at time `t`, interpolated between the ODOM lines around it (clamped to the
/// first and last line).
Pose2 odom_at(const std::vector<OdometryRecord>& odometry, double t) {
  const auto after = std::lower_bound(
      odometry.begin(), odometry.end(), t,
      [](const OdometryRecord& record, double time) { return record.timestamp < time; });
  if (after == odometry.begin()) return odometry.front().pose;
  if (after == odometry.end()) return odometry.back().pose;
  const OdometryRecord& before = *(after - 1);
  const double span = after->timestamp - before.timestamp;
  const double w = span > 0.0 ? (t - before.timestamp) / span : 0.0;
  const Pose2 step = relative_pose(before.pose, after->pose);
  return compose(before.pose, {w * step.x, w * step.y, w * step.theta});
}

/// The odometry pose at each scan run through, with the options' noise when set.
std::vector<Pose2> odometry_of(const CarmenLog& log, const std::vector<std::size_t>& scans,
                               const LogTrackingOptions& options) {
  std::vector<Pose2> path;
  path.reserve(scans.size());
  for (std::size_t index : scans) {
    const LaserRecord& record = log.lasers[index];
    if (!options.raw_odometry.empty()) {
      path.push_back(options.raw_odometry[index]);
      continue;
    }
    path.push_back(options.odometry == OdometrySource::Laser
                       ? record.robot_pose
                       : odom_at(log.odometry, record.timestamp));
  }
  if (!options.odometry_noise) return path;
  Rng rng(options.seed);
  return drifting_odometry(path, *options.odometry_noise, rng);
}

/// Position (m) and heading (degrees) error of `estimate` against `truth`.
void measure_error(TrackStep& step, const Pose2& truth) {
  step.error_m = std::hypot(step.estimate.pose.x - truth.x, step.estimate.pose.y - truth.y);
  step.error_deg = std::abs(normalize_angle(step.estimate.pose.theta - truth.theta)) * 180.0 /
                   3.14159265358979323846;
}

/// add_observation of one scan, timed; an error names the scan's line.
TrackStep observe(Localizer& localizer, const LaserRecord& record, std::size_t index) {
  const auto start = std::chrono::steady_clock::now();
  try {
    localizer.add_observation(record.timestamp, record.scan);
  } catch (const Error& e) {
    throw Error("scan " + std::to_string(index) + " (line " + std::to_string(record.line) +
                "): " + e.what());
  }
  TrackStep step;
  step.timing_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  step.index = index;
  step.time = record.timestamp;
  step.estimate = localizer.estimate();
  step.status = localizer.status();
  measure_error(step, record.robot_pose);
  return step;
}

}  // namespace

void validate(const LogTrackingOptions& options, const CarmenLog& log) {
  if (options.every < 1)
    throw Error("--every must be at least 1, got " + std::to_string(options.every));
  if (log.lasers.empty()) throw Error("log: no laser scan (FLASER or ROBOTLASER1 line)");
  for (std::size_t k = 0; k < options.scans.size(); ++k) {
    if (options.scans[k] >= log.lasers.size() ||
        (k > 0 && options.scans[k] <= options.scans[k - 1])) {
      throw Error("scans to track: index " + std::to_string(options.scans[k]) +
                  " is outside the log's " + std::to_string(log.lasers.size()) +
                  " scans or not after the one before");
    }
  }
  if (options.odometry == OdometrySource::Odom && options.raw_odometry.empty()) {
    check_odom_lines(log);
  }
  if (!options.raw_odometry.empty() && options.raw_odometry.size() != log.lasers.size()) {
    throw Error("raw odometry: " + std::to_string(options.raw_odometry.size()) +
                " poses for the log's " + std::to_string(log.lasers.size()) + " scans");
  }
  if (options.odometry_noise) validate(*options.odometry_noise);
  if (options.prior) {
    const Pose2& p = *options.prior;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.theta)) {
      throw Error("--prior must be finite");
    }
  }
}

void track_log(const CarmenLog& log, const OccupancyMap& map, const LogTrackingOptions& options,
               const std::function<void(const TrackStep&)>& on_step) {
  validate(options, log);
  Localizer localizer(map, options.laser, options.localizer);
  track_log(log, localizer, options, on_step);
}

void track_log(const CarmenLog& log, Localizer& localizer, const LogTrackingOptions& options,
               const std::function<void(const TrackStep&)>& on_step) {
  validate(options, log);
  const std::vector<std::size_t> scans = selected_scans(options, log);
  const std::vector<Pose2> odometry = odometry_of(log, scans, options);
  localizer.reset();
  double travelled_m = 0.0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    if (k > 0) {
      travelled_m +=
          std::hypot(odometry[k].x - odometry[k - 1].x, odometry[k].y - odometry[k - 1].y);
    }
    localizer.add_odometry(odometry[k]);
    if (k == 0 && options.prior) localizer.set_prior(*options.prior, options.prior_covariance);
    if (k % static_cast<std::size_t>(options.every) != 0) continue;
    TrackStep step = observe(localizer, log.lasers[scans[k]], scans[k]);
    step.travelled_m = travelled_m;
    step.odometry = odometry[k];
    on_step(step);
    if (options.max_travel_m > 0.0 && travelled_m >= options.max_travel_m) return;
  }
}

bool right(const TrackStep& step, const GlobalTrialOptions& options) {
  return step.estimate.verdict == Verdict::Localized && step.error_m <= options.success_m &&
         step.error_deg <= options.success_deg;
}

namespace {

/// One trial from candidates[first] on.
GlobalTrial global_trial(const CarmenLog& log, Localizer& localizer, LogTrackingOptions tracking,
                         const std::vector<std::size_t>& candidates, std::size_t first,
                         const GlobalTrialOptions& options) {
  tracking.prior.reset();
  tracking.scans.assign(candidates.begin() + static_cast<std::ptrdiff_t>(first), candidates.end());
  tracking.max_travel_m = options.drive_m;
  GlobalTrial trial;
  trial.start = candidates[first];
  bool first_step = true;
  track_log(log, localizer, tracking, [&](const TrackStep& step) {
    if (first_step) trial.standstill = step;
    first_step = false;
    trial.end = step;
    const bool localized = step.estimate.verdict == Verdict::Localized;
    if (localized && !trial.localized_after_m) trial.localized_after_m = step.travelled_m;
    trial.wrong_localized += localized && !right(step, options);
  });
  return trial;
}

}  // namespace

void run_global_trials(const CarmenLog& log, Localizer& localizer,
                       const LogTrackingOptions& tracking,
                       const std::vector<std::size_t>& candidates,
                       const GlobalTrialOptions& options,
                       const std::function<void(const GlobalTrial&)>& on_trial) {
  if (candidates.empty()) throw Error("global trials: no scan to start from");
  if (options.trials < 1) throw Error("global trials: --trials must be at least 1");
  if (!(options.drive_m >= 0.0) || !std::isfinite(options.drive_m)) {
    throw Error("global trials: the drive length must be finite and >= 0");
  }
  validate(options.shard);
  Rng rng(options.seed);
  for (int t = 0; t < options.trials; ++t) {
    const std::size_t first = static_cast<std::size_t>(rng.uniform() * candidates.size());
    if (!options.shard.owns(t)) continue;  // every start is drawn: the shards see the same
    LogTrackingOptions noisy = tracking;
    noisy.seed = tracking.seed + static_cast<std::uint64_t>(t);
    GlobalTrial trial = global_trial(log, localizer, noisy, candidates,
                                     std::min(first, candidates.size() - 1), options);
    trial.trial = t;
    on_trial(trial);
  }
}

}  // namespace gridloc
