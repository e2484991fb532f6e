// What one localization in the sectors reads and remembers: the scan's checks and view, the
// range residual of a pose, and the memo of residuals and polished poses.
#include "localization_problem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc::sectors_detail {
namespace {

/// How well the map explains the scan at a pose: each return's range (every `stride`-th)
/// against the range cast along its beam on the polygons, the difference capped, averaged.
/// Beams without return do not count: real scanners drop beams on glass and dark surfaces.
double range_residual(const Problem& problem, const Pose2& pose, int stride) {
  const RangeScan& scan = problem.view.scan;
  const std::vector<int>& hits = problem.view.hits;
  const Eigen::Vector2d origin(pose.x, pose.y);
  double sum = 0.0;
  int used = 0;
  for (std::size_t h = 0; h < hits.size(); h += static_cast<std::size_t>(stride), ++used) {
    const int i = hits[h];
    const double a = pose.theta + scan.angles[i];
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    double expected = scan.max_range;
    for (const Wall& wall : problem.walls) {
      const Eigen::Vector2d &e = wall.e, w = wall.a - origin;
      const double den = cross(dir, e);
      if (std::abs(den) < 1e-12) continue;  // parallel: not seen
      const double t = cross(w, e) / den, u = cross(w, dir) / den;
      if (t > 0.0 && t < expected && u >= 0.0 && u <= 1.0) expected = t;
    }
    sum += std::min(problem.options.residual_cap_m, std::abs(scan.ranges[i] - expected));
  }
  return sum / used;
}

}  // namespace

/// Seed 000 §3.1's scan is a full turn: angles increase and cover 360 deg without a large
/// gap. Throws gridloc::Error naming the fault otherwise (a 180 or 270 deg field of view, a
/// scan in degrees, clockwise beams).
void check_full_turn(const RangeScan& scan) {
  const std::size_t n = scan.angles.size();
  if (n < 3) throw Error("sectors: a scan of " + std::to_string(n) + " beams is no full turn");
  std::vector<double> steps;
  double widest = 0.0;
  std::size_t after = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double d = scan.angles[i] - scan.angles[i - 1];
    if (!(d > 0.0)) {
      throw Error("sectors: scan angles must increase (counter-clockwise beams); beam " +
                  std::to_string(i) + " is at " + std::to_string(scan.angles[i]) + " rad after " +
                  std::to_string(scan.angles[i - 1]));
    }
    steps.push_back(d);
    if (d > widest) widest = d, after = i - 1;
  }
  const double span = scan.angles.back() - scan.angles.front();
  if (span >= 2.0 * std::numbers::pi + 1e-9) {
    throw Error("sectors: scan angles span " + std::to_string(span) +
                " rad, more than a turn (radians expected)");
  }
  const double closing = 2.0 * std::numbers::pi - span;
  if (closing > widest) widest = closing, after = n - 1;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                   steps.end());
  const double step = steps[steps.size() / 2];
  if (widest > std::max(4.0 * step, 0.2)) {
    throw Error("sectors: the scan covers " +
                std::to_string(std::lround(rad2deg(2.0 * std::numbers::pi - widest))) +
                " deg (a gap of " + std::to_string(std::lround(rad2deg(widest))) +
                " deg after beam " + std::to_string(after) +
                "); visibility sectors need a full 360 deg turn");
  }
}

/// The options' ranges; throws gridloc::Error naming them.
void check_options(const SectorLocalizationOptions& options) {
  if (options.max_deleted_pairs < 0 || options.line_points < 2 ||
      !(options.ambiguity_residual_m >= 0.0) || !(options.residual_cap_m > 0.0) ||
      !(options.rough_residual_m > 0.0) || options.max_deleted_jumps < 0) {
    throw Error(
        "SectorLocalizationOptions: max_deleted_pairs and max_deleted_jumps must be >= 0, "
        "line_points >= 2, ambiguity_residual_m >= 0, residual_cap_m and rough_residual_m > 0");
  }
}

/// The scan's label, points, returns and beam step (see ScanView).
ScanView view_scan(const RangeScan& scan, const ScanLabelOptions& label_options) {
  ScanView view{scan, construct_scan_label(scan, label_options), {}, {}, {}, 0.0};
  const int n = static_cast<int>(scan.ranges.size());
  view.points.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double r = std::min(scan.ranges[i], scan.max_range);
    view.points[i] = r * Eigen::Vector2d(std::cos(scan.angles[i]), std::sin(scan.angles[i]));
  }
  for (int i = 0; i < n; ++i) {
    if (scan.ranges[i] < scan.max_range) view.hits.push_back(i);
  }
  for (int i = 0; i < n; ++i) {
    if (scan.ranges[i] < scan.max_range) view.returns.push_back(view.points[i]);
  }
  double beam_step = 2.0 * std::numbers::pi / n;
  for (int i = 1; i < n; ++i)
    beam_step = std::max(beam_step, std::abs(normalize_angle(scan.angles[i] - scan.angles[i - 1])));
  view.beam_step = std::min(beam_step, 0.2);
  return view;
}

double PoseMemo::residual_at(const Problem& problem, const Pose2& pose) {
  for (const auto& [p, r] : residuals) {
    if (std::abs(p.x - pose.x) < 1e-9 && std::abs(p.y - pose.y) < 1e-9 &&
        std::abs(p.theta - pose.theta) < 1e-9) {
      return r;
    }
  }
  residuals.emplace_back(pose, range_residual(problem, pose, 1));
  return residuals.back().second;
}

/// `rough` polished on the walls, remembered; with `gated`, left rough when the scan
/// refutes it.
Pose2 PoseMemo::polished(const Problem& problem, const Pose2& rough, bool gated) {
  for (const auto& [r, p] : polishes) {
    if (r.x == rough.x && r.y == rough.y && r.theta == rough.theta) return p;
  }
  // A rough pose from located corners that the scan plainly refutes (a quarter of the
  // returns, capped mean) is not worth a polish: wrong matches are most of the candidates,
  // and the polish most of the cost. Right matches are a few centimetres off before the
  // polish, far below the bar. Look-alike placements rest on two corners only and can be
  // tens of centimetres off: they are always polished.
  const bool refuted =
      gated && range_residual(problem, rough, 4) > problem.options.rough_residual_m;
  const Pose2 p = refuted ? rough : polish(problem.view.returns, problem.walls, rough);
  polishes.emplace_back(rough, p);
  return polishes.back().second;
}

}  // namespace gridloc::sectors_detail
