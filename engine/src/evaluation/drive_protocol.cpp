// The drive protocol: a short drive's fused firings against the last firing alone.
#include "gridloc/engine/evaluation/drive_protocol.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/odometry_noise.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {
namespace {

/// Throws unless the options describe a drive that can be run.
void check(const DriveEvalOptions& options) {
  if (options.trials < 1) throw Error("drive evaluation: trials must be at least 1");
  if (options.firings < 2) throw Error("drive evaluation: firings must be at least 2");
  if (!(options.drive_m > 0.0) || !std::isfinite(options.drive_m) || options.drive_m > 20.0) {
    throw Error("drive evaluation: drive_m must lie in (0, 20] m");
  }
  if (!(options.odometry_noise_frac >= 0.0) || !(options.odometry_noise_rad_per_m >= 0.0) ||
      !std::isfinite(options.odometry_noise_frac) ||
      !std::isfinite(options.odometry_noise_rad_per_m)) {
    throw Error("drive evaluation: the odometry noise must be finite and >= 0");
  }
  validate(options.fusion);
}

/// One trial: the true path (oldest pose first, the truth last), the firings at its poses
/// with drifting odometry, and the window of a windowed search.
struct DriveTrial {
  std::vector<Pose2> path;
  std::vector<OdometryFiring> drive;
  SearchWindow window;
};

/// A straight path of `options.firings` poses ending at a free pose, every pose free.
std::vector<Pose2> draw_path(const OccupancyMap& map, const SonarRing& ring,
                             const DriveEvalOptions& options, Rng& rng) {
  const double step = options.drive_m / (options.firings - 1);
  for (int attempt = 0; attempt < 2000; ++attempt) {
    const Pose2 truth = sample_free_pose(map, ring, options.clearance_m, rng);
    std::vector<Pose2> path;
    for (int k = options.firings - 1; k >= 0; --k) {
      const Pose2 pose = compose(truth, {-step * k, 0.0, 0.0});
      if (!pose_is_free(map, ring, pose, options.clearance_m)) break;
      path.push_back(pose);
    }
    if (static_cast<int>(path.size()) == options.firings) return path;
  }
  throw Error("drive evaluation: found no free straight path of " +
              std::to_string(options.drive_m) + " m on this map");
}

DriveTrial draw_trial(const OccupancyMap& map, const SonarRing& ring,
                      const DriveEvalOptions& options, Rng& rng) {
  DriveTrial trial;
  trial.path = draw_path(map, ring, options, rng);
  const std::vector<Pose2> odometry = drifting_odometry(
      trial.path, {options.odometry_noise_frac, options.odometry_noise_rad_per_m}, rng);
  for (std::size_t k = 0; k < trial.path.size(); ++k) {
    SonarSimOptions noise = options.noise;
    noise.seed = rng.next();
    trial.drive.push_back({odometry[k], simulate_sonar(map, ring, trial.path[k], noise)});
  }
  trial.window = perturb_prior(options.window, trial.path.back(), false, map.geometry, rng).window;
  return trial;
}

/// The search's options with the reach covering every fused drive: a re-mounted sonar lies
/// at most the fusion window's path length farther out than on the robot.
CorrelationOptions search_options(const DriveEvalOptions& options, const SonarRing& ring) {
  CorrelationOptions search = options.search;
  search.reach_m = std::max(search.reach_m, ring.reach() + options.fusion.max_distance_m);
  return search;
}

/// Estimates one observation and counts its outcome against `truth`.
void score(const CorrelationEstimator& estimator, const Observation& observation,
           const DriveEvalOptions& options, const DriveTrial& trial, DriveEvalTally& tally,
           std::vector<double>& ms) {
  const SearchWindow window = options.global ? estimator.global_window(observation) : trial.window;
  const auto start = std::chrono::steady_clock::now();
  const Estimate e = estimator.estimate(observation, window);
  ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  const Pose2& truth = trial.path.back();
  const bool success =
      std::hypot(e.pose.x - truth.x, e.pose.y - truth.y) <= options.success_xy &&
      std::abs(normalize_angle(e.pose.theta - truth.theta)) <= options.success_theta;
  tally.successes += success;
  tally.localized += e.verdict == Verdict::Localized;
  tally.ambiguous += e.verdict == Verdict::Ambiguous;
  tally.not_localized += e.verdict == Verdict::NotLocalized;
  tally.confident_wrong += e.verdict == Verdict::Localized && !success;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// The rows of one map: both ways of localizing on the same trials.
DriveEvalRow run_map(const EvalMap& map, std::size_t map_index, const SonarRing& ring,
                     const DriveEvalOptions& options, const std::function<void()>& done) {
  const CorrelationEstimator estimator(map.map, ring, search_options(options, ring));
  Rng rng(options.seed * 1000003u + map_index);
  DriveEvalRow row{map.name, options.trials, {}, {}};
  std::vector<double> standstill_ms, drive_ms;
  for (int t = 0; t < options.trials; ++t) {
    const DriveTrial trial = draw_trial(map.map, ring, options, rng);
    score(estimator, Observation{trial.drive.back().ranges}, options, trial, row.standstill,
          standstill_ms);
    const FusedFirings fused = fuse_firings(ring, trial.drive, options.fusion);
    score(estimator, Observation{fused.ranges, std::nullopt, fused.rejected, fused.ring}, options,
          trial, row.drive, drive_ms);
    done();
  }
  row.standstill.median_ms = median(standstill_ms);
  row.drive.median_ms = median(drive_ms);
  return row;
}

}  // namespace

DriveEvalReport run_drive_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                                     const DriveEvalOptions& options,
                                     const std::function<void(int, int)>& progress) {
  check(options);
  if (maps.empty()) throw Error("drive evaluation: no map");
  const int total = options.trials * static_cast<int>(maps.size());
  int finished = 0;
  const auto done = [&] {
    if (progress) progress(++finished, total);
  };
  DriveEvalReport report;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    report.maps.push_back(run_map(maps[m], m, ring, options, done));
  }
  return report;
}

}  // namespace gridloc
