#include "gridloc/engine/evaluation/hallway_trials.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_disturbances.hpp"
#include "gridloc/sensors/segment_world.hpp"

namespace gridloc {

std::string to_string(OutlierKind kind) {
  switch (kind) {
    case OutlierKind::None:
      return "none";
    case OutlierKind::Scattered:
      return "scattered";
    case OutlierKind::Appearing:
      return "appearing";
  }
  return "?";
}

OutlierKind parse_outlier_kind(const std::string& name) {
  for (OutlierKind kind : {OutlierKind::None, OutlierKind::Scattered, OutlierKind::Appearing}) {
    if (to_string(kind) == name) return kind;
  }
  throw Error("outliers must be none, scattered or appearing, not '" + name + "'");
}

namespace {

/// Seed `seed`'s trial: the hallway scanned at the origin (the reference) and after seed
/// 004's motion (the current scan, with its outliers), both with seeded noise; ICP from the
/// origin.
IcpResult match_hallway_trial(const std::vector<WallSegment>& walls,
                              const HallwayTrialsOptions& options, std::uint64_t seed) {
  const auto scan_at = [&](const Pose2& pose) {
    return simulate_segment_scan(walls, pose, 720, deg2rad(-180.0), deg2rad(0.5), 8.0);
  };
  RangeScan reference = scan_at({0, 0, 0});
  RangeScan current = scan_at(kSeed004Motion);
  add_range_noise(reference, options.noise_m, 1000 + 2 * seed);
  add_range_noise(current, options.noise_m, 1001 + 2 * seed);
  auto points = scan_returns(current);
  if (options.outliers == OutlierKind::Scattered) {
    points = scatter_outliers(points, options.share, 3.0, seed);
  }
  if (options.outliers == OutlierKind::Appearing) {
    points = appear_obstacles(points, options.share, seed);
  }
  return match_scans(scan_returns(reference), points, Pose2{}, options.icp);
}

}  // namespace

HallwayReport run_hallway_trials(const HallwayTrialsOptions& options) {
  if (options.seeds < 1) {
    throw Error("hallway trials: seeds must be >= 1, got " + std::to_string(options.seeds));
  }
  const std::vector<WallSegment> walls = seed004_hallway();
  HallwayReport report;
  report.seeds = options.seeds;
  for (int s = 1; s <= options.seeds; ++s) {
    const IcpResult match = match_hallway_trial(walls, options, static_cast<std::uint64_t>(s));
    const double dx = std::abs(match.pose.x - kSeed004Motion.x);
    const double dy = std::abs(match.pose.y - kSeed004Motion.y);
    const double dt = rad2deg(std::abs(normalize_angle(match.pose.theta - kSeed004Motion.theta)));
    report.converged += match.converged ? 1 : 0;
    if (std::hypot(dx, dy) < options.success_xy && dt < options.success_deg) {
      ++report.successes;
      report.mean_error_x_m += dx;
      report.mean_error_y_m += dy;
      report.mean_error_deg += dt;
      report.mean_iterations += match.iterations;
    }
  }
  const double n = std::max(report.successes, 1);
  report.mean_error_x_m /= n;
  report.mean_error_y_m /= n;
  report.mean_error_deg /= n;
  report.mean_iterations /= n;
  return report;
}

}  // namespace gridloc
