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
  for (OutlierKind k : {OutlierKind::None, OutlierKind::Scattered, OutlierKind::Appearing}) {
    if (to_string(k) == name) return k;
  }
  throw Error("outliers must be none, scattered or appearing, not '" + name + "'");
}

HallwayReport run_hallway_trials(const HallwayTrialsOptions& o) {
  if (o.seeds < 1)
    throw Error("hallway trials: seeds must be >= 1, got " + std::to_string(o.seeds));
  const std::vector<WallSegment> walls = seed004_hallway();
  const auto scan_at = [&](const Pose2& pose) {
    return simulate_segment_scan(walls, pose, 720, deg2rad(-180.0), deg2rad(0.5), 8.0);
  };
  HallwayReport report;
  report.seeds = o.seeds;
  for (int s = 1; s <= o.seeds; ++s) {
    const auto seed = static_cast<std::uint64_t>(s);
    RangeScan ref = scan_at({0, 0, 0});
    RangeScan cur = scan_at(kSeed004Motion);
    add_range_noise(ref, o.noise_m, 1000 + 2 * seed);
    add_range_noise(cur, o.noise_m, 1001 + 2 * seed);
    auto points = scan_returns(cur);
    if (o.outliers == OutlierKind::Scattered) points = scatter_outliers(points, o.share, 3.0, seed);
    if (o.outliers == OutlierKind::Appearing) points = appear_obstacles(points, o.share, seed);
    const IcpResult r = match_scans(scan_returns(ref), points, Pose2{}, o.icp);
    const double dx = std::abs(r.pose.x - kSeed004Motion.x);
    const double dy = std::abs(r.pose.y - kSeed004Motion.y);
    const double dt = rad2deg(std::abs(normalize_angle(r.pose.theta - kSeed004Motion.theta)));
    report.converged += r.converged ? 1 : 0;
    if (std::hypot(dx, dy) < o.success_xy && dt < o.success_deg) {
      ++report.successes;
      report.mean_error_x_m += dx;
      report.mean_error_y_m += dy;
      report.mean_error_deg += dt;
      report.mean_iterations += r.iterations;
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
