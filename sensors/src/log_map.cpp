#include "gridloc/sensors/log_map.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "gridloc/grids/cell_walk.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace {

/// Bytes per cell while drawing: two uint16 beam counts and the map's state.
constexpr double kBytesPerCell = 5.0;

void require_positive(double value, const char* field) {
  gridloc::require_positive(value, "map from log", field);
}

void require_non_negative(double value, const char* field) {
  gridloc::require_non_negative(value, "map from log", field);
}

/// validate() of a scan, except that a scan without any return passes: it draws no hit.
void check_scan(const RangeScan& scan) {
  const bool any_return = std::any_of(scan.ranges.begin(), scan.ranges.end(),
                                      [&](double r) { return r < scan.max_range; });
  if (any_return) return validate(scan);
  RangeScan with_return = scan;  // rare: checked with one return added
  with_return.angles.push_back(0.0);
  with_return.ranges.push_back(0.0);
  validate(with_return);
}

/// Throws gridloc::Error for no index, an index past the log, a laser pose that is not finite
/// or a scan that fails check_scan.
void check_scans(const std::vector<LaserRecord>& lasers, const std::vector<std::size_t>& indices) {
  if (indices.empty()) throw Error("map from log: no scan to draw the map from");
  for (const std::size_t k : indices) {
    if (k >= lasers.size()) {
      throw Error("map from log: scan index " + std::to_string(k) + " is past the log's " +
                  std::to_string(lasers.size()) + " scans");
    }
    const LaserRecord& r = lasers[k];
    const std::string where = "map from log: the scan of line " + std::to_string(r.line) + ": ";
    if (!std::isfinite(r.laser_pose.x) || !std::isfinite(r.laser_pose.y) ||
        !std::isfinite(r.laser_pose.theta)) {
      throw Error(where + "the laser pose is not finite");
    }
    try {
      check_scan(r.scan);
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
  }
}

/// One beam as drawn: from the laser to `to` (world frame, m); `hit` when its end is a return.
struct Beam {
  Eigen::Vector2d from, to;
  bool hit = false;
};

/// Beam k of `record` as options draw it, or false when it is not drawn (a zero range, a beam
/// without a usable return when no_return_free_m is 0).
bool drawn_beam(const LaserRecord& record, std::size_t k, const LogMapOptions& options,
                Beam& beam) {
  const double range = record.scan.ranges[k];
  beam.hit = range < record.scan.max_range && range <= options.max_range_m;
  if (range <= 0.0 || (!beam.hit && options.no_return_free_m <= 0.0)) return false;
  const double length = beam.hit ? range : options.no_return_free_m;
  const Pose2& p = record.laser_pose;
  const double a = p.theta + record.scan.angles[k];
  beam.from = {p.x, p.y};
  beam.to = {p.x + length * std::cos(a), p.y + length * std::sin(a)};
  return true;
}

/// Calls visit(beam) for every beam the scans `indices` draw.
template <typename Visit>
void for_each_beam(const std::vector<LaserRecord>& lasers, const std::vector<std::size_t>& indices,
                   const LogMapOptions& options, Visit&& visit) {
  Beam beam;
  for (const std::size_t i : indices) {
    for (std::size_t k = 0; k < lasers[i].scan.ranges.size(); ++k) {
      if (drawn_beam(lasers[i], k, options, beam)) visit(beam);
    }
  }
}

/// The grid spanning the first scan's laser position and every drawn beam plus the margin; throws
/// gridloc::Error when it would hold more than options.limits.max_cells cells or need more than
/// options.limits.max_memory_mb.
GridGeometry grid_for(const std::vector<LaserRecord>& lasers,
                      const std::vector<std::size_t>& indices, const LogMapOptions& options) {
  const Eigen::Vector2d first(lasers[indices.front()].laser_pose.x,
                              lasers[indices.front()].laser_pose.y);
  Eigen::Vector2d lo = first, hi = first;
  for_each_beam(lasers, indices, options, [&](const Beam& b) {
    lo = lo.cwiseMin(b.from).cwiseMin(b.to);
    hi = hi.cwiseMax(b.from).cwiseMax(b.to);
  });
  const Eigen::Vector2d size_m = (hi - lo).array() + 2.0 * options.margin_m;
  const double width = std::ceil(size_m.x() / options.resolution) + 1.0;
  const double height = std::ceil(size_m.y() / options.resolution) + 1.0;
  const std::string what = "map from log: the map of " + message_number(size_m.x()) + " m x " +
                           message_number(size_m.y()) + " m at " +
                           message_number(options.resolution) + " m";
  const double cells = check_grid_cells(width, height, options.limits, what);
  check_memory(kBytesPerCell * cells, options.limits, what);
  GridGeometry g;
  g.resolution = options.resolution;
  g.origin = lo.array() - options.margin_m;
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);
  return g;
}

/// Per cell, how many beams ended in it and how many crossed it (saturating at 65535).
struct BeamCounts {
  std::vector<std::uint16_t> hits, passes;

  explicit BeamCounts(std::size_t cells) : hits(cells, 0), passes(cells, 0) {}
  static void add(std::uint16_t& count) { count += count < 65535; }
};

/// Counts a beam: every cell it crosses before its end cell is passed (Amanatides-Woo
/// traversal, forced towards the end cell so it always arrives there), the end cell is hit
/// when the beam ends in a return and passed otherwise.
void count_beam(const GridGeometry& g, const Beam& beam, BeamCounts& counts) {
  const Eigen::Vector2d a = (beam.from - g.origin) / g.resolution;
  const Eigen::Vector2d b = (beam.to - g.origin) / g.resolution;
  const int ex = static_cast<int>(std::floor(b.x())), ey = static_cast<int>(std::floor(b.y()));
  CellWalk walk(a.x(), a.y(), b.x() - a.x(), b.y() - a.y());
  while (walk.ix != ex || walk.iy != ey) {
    BeamCounts::add(counts.passes[g.index(walk.ix, walk.iy)]);
    walk.step_towards(ex, ey);
  }
  BeamCounts::add((beam.hit ? counts.hits : counts.passes)[g.index(ex, ey)]);
}

CellState classify(std::uint16_t hits, std::uint16_t passes, const LogMapOptions& options) {
  if (hits >= options.min_hits && hits >= options.occupied_ratio * (hits + passes)) {
    return CellState::Occupied;
  }
  return passes >= options.min_passes ? CellState::Free : CellState::Unknown;
}

}  // namespace

void validate(const LogMapOptions& options) {
  require_positive(options.resolution, "resolution");
  require_positive(options.max_range_m, "max_range_m");
  require_non_negative(options.no_return_free_m, "no_return_free_m");
  require_non_negative(options.margin_m, "margin_m");
  if (options.min_hits < 1 || options.min_hits > 65535) {
    throw Error("map from log: min_hits must be in [1, 65535], got " +
                std::to_string(options.min_hits));
  }
  if (options.min_passes < 1 || options.min_passes > 65535) {
    throw Error("map from log: min_passes must be in [1, 65535], got " +
                std::to_string(options.min_passes));
  }
  if (!(options.occupied_ratio > 0.0 && options.occupied_ratio <= 1.0)) {
    throw Error("map from log: occupied_ratio must be in (0, 1], got " +
                message_number(options.occupied_ratio));
  }
  options.limits.validate();
}

OccupancyMap map_from_log(const std::vector<LaserRecord>& lasers,
                          const std::vector<std::size_t>& indices, const LogMapOptions& options) {
  validate(options);
  check_scans(lasers, indices);
  const GridGeometry geometry = grid_for(lasers, indices, options);
  BeamCounts counts(geometry.size());
  for_each_beam(lasers, indices, options,
                [&](const Beam& beam) { count_beam(geometry, beam, counts); });
  OccupancyMap map(geometry, CellState::Unknown);
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    map.cells[c] = classify(counts.hits[c], counts.passes[c], options);
  }
  return map;
}

OccupancyMap map_from_log(const CarmenLog& log, const std::vector<std::size_t>& indices,
                          const LogMapOptions& options) {
  return map_from_log(log.lasers, indices, options);
}

CellCounts count_cells(const OccupancyMap& map) {
  CellCounts counts;
  for (const CellState s : map.cells) {
    (s == CellState::Occupied ? counts.occupied
     : s == CellState::Free   ? counts.free
                              : counts.unknown)++;
  }
  return counts;
}

}  // namespace gridloc
