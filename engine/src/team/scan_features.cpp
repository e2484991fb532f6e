// Seed 003 ch. III A-B and VI B: the corners, walls and saturation points of a short-range
// scan. One pipeline for simulated and real scans: runs of returns, split-and-merge into
// straight walls fitted by least squares, corners where two fitted walls of a run meet (the
// intersection of their lines, eq. 6.3), a one-wall convex corner where a wall's run ends in a
// jump away from the robot, and the walls no corner claims.
#include "gridloc/engine/team/scan_features.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/grids/planar.hpp"
#include "scan_runs.hpp"

namespace gridloc {
namespace {

using team_detail::FittedLine;
using team_detail::RunNeighbour;
using team_detail::ScanRun;
using team_detail::WallPiece;

void check_option(bool ok, const char* field, const char* rule, double value) {
  require_option(ok, "FeatureOptions", field, value, std::string("must be ") + rule);
}

/// validate(scan) less its "no return" rule: a scan that saw nothing has no feature, which is
/// no error here. The saturated readings count as returns for the check.
void check_scan(const RangeScan& scan) {
  RangeScan probe = scan;
  for (double& r : probe.ranges) {
    if (r >= scan.max_range) r = 0.0;
  }
  validate(probe);
}

/// The intersection of two lines that are not parallel.
Eigen::Vector2d intersection(const FittedLine& a, const FittedLine& b) {
  return line_intersection(a.centroid, a.direction, b.centroid, b.direction);
}

/// The feature's walls: their ends in the scan (saturation1, saturation2), fit and points.
void set_walls(ScanFeature& f, const ScanRun& run, const WallPiece& first, const WallPiece& last,
               std::initializer_list<const WallPiece*> walls) {
  f.saturation1 = first.line.project(run.at(first.begin));
  f.saturation2 = last.line.project(run.at(last.end - 1));
  double sum_squares = 0.0;
  f.points = 0;
  for (const WallPiece* w : walls) {
    sum_squares += w->sum_squares;
    f.points += w->count();
  }
  f.fit_rms_m = std::sqrt(sum_squares / f.points);
}

/// The corner where wall a of a run turns into the next wall b: when they turn by min_turn or
/// more and their lines meet within gap_m of both walls' ends (farther, something lies
/// between them that is no corner).
std::optional<ScanFeature> corner_between(const ScanRun& run, const WallPiece& a,
                                          const WallPiece& b, const FeatureOptions& options) {
  const Eigen::Vector2d& u = a.line.direction;
  const Eigen::Vector2d& v = b.line.direction;
  const double turn = std::atan2(cross(u, v), u.dot(v));  // > 0: left, counter-clockwise
  if (std::abs(turn) < options.min_turn) return std::nullopt;
  const Eigen::Vector2d c = intersection(a.line, b.line);
  if ((c - run.at(a.end - 1)).norm() > options.gap_m ||
      (c - run.at(b.begin)).norm() > options.gap_m) {
    return std::nullopt;
  }
  ScanFeature f;
  f.kind = turn > 0.0 ? FeatureKind::ConcaveCorner : FeatureKind::ConvexCorner;
  f.point = c;
  f.wall1 = u;
  f.wall2 = v;
  f.free_angle = std::numbers::pi - turn;
  set_walls(f, run, a, b, {&a, &b});
  return f;
}

/// Whether a run's end at return `end` of wall `line`, next to reading `n`, is a convex corner
/// hiding the other wall: the end is no saturation point, the neighbour's beam reads farther
/// (or nothing: a jump nearer is something in front of this wall, not its corner), and the
/// wall, had it gone on, would have met that beam nearer than it read (else the wall may go on
/// unseen: at a glancing angle, beyond the max range or between the beams).
bool hides_a_wall(const RunNeighbour& n, const Eigen::Vector2d& end, const FittedLine& line,
                  double max_range, const FeatureOptions& options) {
  if (!n.exists) return false;  // the edge of a scan that is no full turn: nothing known
  if (end.norm() >= max_range - options.saturation_margin_m) return false;
  if (!n.saturated && n.range <= end.norm()) return false;
  const double toward_wall = n.beam.dot(line.normal());  // < 0 when the beam heads for it
  if (toward_wall >= 0.0) return false;
  const double wall_range = line.centroid.dot(line.normal()) / toward_wall;
  const double read =
      n.saturated ? max_range - options.saturation_margin_m : n.range - options.split_m;
  return wall_range < read;
}

ScanFeature one_wall_corner(const ScanRun& run, const WallPiece& w, bool arrives) {
  ScanFeature f;
  f.kind = FeatureKind::ConvexCornerOneWall;
  f.point = w.line.project(arrives ? run.at(w.end - 1) : run.at(w.begin));
  f.wall1 = w.line.direction;
  f.seen_wall_arrives = arrives;
  set_walls(f, run, w, w, {&w});
  return f;
}

ScanFeature wall_feature(const ScanRun& run, const WallPiece& w) {
  ScanFeature f;
  f.kind = FeatureKind::Wall;
  f.point = w.line.project(Eigen::Vector2d::Zero());
  f.wall1 = w.line.direction;
  set_walls(f, run, w, w, {&w});
  return f;
}

/// The features of one run's walls: corners between consecutive walls, one-wall corners at
/// the run's ends, and the walls that are part of no corner.
void add_run_features(const ScanRun& run, const std::vector<WallPiece>& walls, double max_range,
                      const FeatureOptions& options, std::vector<ScanFeature>& features) {
  const std::size_t n = walls.size();
  std::vector<bool> in_corner(n, false);
  const std::size_t pairs = n < 2 ? 0 : (run.closed ? n : n - 1);
  for (std::size_t i = 0; i < pairs; ++i) {
    const std::size_t j = (i + 1) % n;
    if (auto corner = corner_between(run, walls[i], walls[j], options)) {
      features.push_back(*corner);
      in_corner[i] = in_corner[j] = true;
    }
  }
  if (!run.closed && n > 0) {
    const WallPiece& first = walls.front();
    const WallPiece& last = walls.back();
    if (first.begin == 0 && hides_a_wall(run.before, run.at(0), first.line, max_range, options)) {
      features.push_back(one_wall_corner(run, first, false));
      in_corner.front() = true;
    }
    if (last.end == run.size() &&
        hides_a_wall(run.after, run.at(run.size() - 1), last.line, max_range, options)) {
      features.push_back(one_wall_corner(run, last, true));
      in_corner.back() = true;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!in_corner[i]) features.push_back(wall_feature(run, walls[i]));
  }
}

}  // namespace

std::string to_string(FeatureKind kind) {
  switch (kind) {
    case FeatureKind::ConcaveCorner:
      return "concave corner";
    case FeatureKind::ConvexCorner:
      return "convex corner";
    case FeatureKind::ConvexCornerOneWall:
      return "convex corner (one wall)";
    case FeatureKind::Wall:
      return "wall";
  }
  return "unknown";
}

void validate(const FeatureOptions& o) {
  check_option(o.split_m > 0.0 && std::isfinite(o.split_m), "split_m", "positive and finite",
               o.split_m);
  check_option(o.gap_m > 0.0 && std::isfinite(o.gap_m), "gap_m", "positive and finite", o.gap_m);
  check_option(o.min_wall_points >= 2, "min_wall_points", "at least 2", o.min_wall_points);
  check_option(o.min_wall_m >= 0.0 && std::isfinite(o.min_wall_m), "min_wall_m",
               "non-negative and finite", o.min_wall_m);
  check_option(o.min_turn > 0.0 && o.min_turn < std::numbers::pi, "min_turn", "in (0, pi)",
               o.min_turn);
  check_option(o.saturation_margin_m >= 0.0 && std::isfinite(o.saturation_margin_m),
               "saturation_margin_m", "non-negative and finite", o.saturation_margin_m);
}

std::vector<ScanFeature> extract_features(const RangeScan& scan, const FeatureOptions& options) {
  check_scan(scan);
  validate(options);
  std::vector<ScanFeature> features;
  for (const ScanRun& run : team_detail::scan_runs(scan, options.gap_m)) {
    const std::vector<WallPiece> walls = team_detail::fitted_walls(run, options);
    add_run_features(run, walls, scan.max_range, options, features);
  }
  std::stable_sort(features.begin(), features.end(),
                   [](const ScanFeature& a, const ScanFeature& b) {
                     if (a.kind != b.kind) return a.kind < b.kind;
                     return a.point.squaredNorm() < b.point.squaredNorm();
                   });
  return features;
}

}  // namespace gridloc
