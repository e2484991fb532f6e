// The correlation estimator's checks of what it is given: options, observations and search
// windows, and the lattice a window spans (with the global window, the largest one).
#include "checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace correlation_detail {

/// Checks the options on their own; throws gridloc::Error naming the first that is wrong.
void check(const CorrelationOptions& options) {
  constexpr std::string_view owner = "correlation options";
  require_option(options.resolution > 0.0 && std::isfinite(options.resolution), owner, "resolution",
                 options.resolution, "must be > 0");
  require_option(options.levels >= 1 && options.levels <= 8, owner, "levels", options.levels,
                 "must be in [1, 8]");
  require_option(options.keep >= 1, owner, "keep", options.keep, "must be >= 1");
  require_option(options.hypotheses >= 1 && options.hypotheses <= 100, owner, "hypotheses",
                 options.hypotheses, "must be in [1, 100]");
  require_option(options.second_peak_floor >= 0.0 && options.second_peak_floor < 1.0, owner,
                 "second_peak_floor", options.second_peak_floor, "must lie in [0, 1)");
  require_option(options.max_bound_depth >= 0 && options.max_bound_depth <= 31, owner,
                 "max_bound_depth", options.max_bound_depth, "must be in [0, 31]");
  require_option(options.covariance_cells >= 0 && options.covariance_cells <= 20, owner,
                 "covariance_cells", options.covariance_cells, "must be in [0, 20]");
  require_option(
      options.covariance_temperature > 0.0 && std::isfinite(options.covariance_temperature), owner,
      "covariance_temperature", options.covariance_temperature, "must be finite and > 0");
  require_non_negative(options.ring_covariance_temperature, owner, "ring_covariance_temperature");
  require_share(options.scan_quantization_share, owner, "scan_quantization_share");
  require_share(options.ring_quantization_share, owner, "ring_quantization_share");
  validate(options.scan);
  options.field.validate();
  // The sonar canvas has two cells of margin beyond the ring's reach: a deeper arc draws
  // outside it (issue 14: --arc-depth 1e11 crashed, 1e300 blamed the padding).
  require_option(options.sonar.arc_depth_cells >= 0.0 && options.sonar.arc_depth_cells <= 2.0,
                 owner, "arc depth", options.sonar.arc_depth_cells, "must lie in [0, 2] cells");
  require_option(options.budget_ms >= 0.0 && std::isfinite(options.budget_ms), owner, "budget_ms",
                 options.budget_ms, "must be finite and >= 0");
  // Options only branch and bound can honour are errors elsewhere, not silently ignored.
  if (options.strategy != SearchStrategy::BranchAndBound &&
      (options.budget_ms > 0.0 || options.heading_intervals)) {
    throw Error(std::string("correlation options: ") +
                (options.budget_ms > 0.0 ? "budget_ms" : "heading_intervals") +
                " needs the branch-and-bound strategy");
  }
  require_option(options.threads >= 1 && options.threads <= 256, owner, "threads", options.threads,
                 "must be in [1, 256]");
  require_option(std::isfinite(options.poses_per_thread) && options.poses_per_thread >= 0.0, owner,
                 "poses_per_thread", options.poses_per_thread, "must be finite and >= 0");
  options.limits.validate();
}

void check_resources(const GridGeometry& map, const CorrelationOptions& options, double reach,
                     const SearchSize& search, bool hits_only) {
  const double width_m = map.width * map.resolution, height_m = map.height * map.resolution;
  // Every lattice pose is a search cell's centre: the first lies inside the map only if one
  // search cell fits in it (else the answer would lie outside the map).
  if (options.resolution > std::min(width_m, height_m)) {
    std::ostringstream m;
    m << "correlation options: resolution " << options.resolution << " m (the search step, "
      << "gridloc --step-xy) is coarser than the map (" << width_m << " x " << height_m
      << " m): one search cell must fit in it; use a smaller step or a larger map";
    throw Error(m.str());
  }
  const int built = options.strategy == SearchStrategy::Multires ? options.levels : 1;
  for (int l = 0; l < built; ++l) {
    const double res = options.resolution * static_cast<double>(1 << l);
    const GlobalGridSize size = global_grid_size(map, res, reach);
    std::ostringstream what;
    what << "correlation estimator: the global grid at " << res << " m";
    check_grid_cells(size.width, size.height, options.limits, what.str());
    check_grid_cells(size.width + 2.0 * size.pad, size.height + 2.0 * size.pad, options.limits,
                     what.str() + " padded by the reach");
  }
  std::ostringstream what;
  what << "correlation estimator: the grids of a " << width_m << " x " << height_m << " m map at "
       << options.resolution << " m";
  if (search.headings > 0.0) {
    what << " and a search of " << search.translations << " cells x " << search.headings
         << " headings";
  }
  check_memory(correlation_memory_bytes(map, options, reach, search, hits_only), options.limits,
               what.str());
}

/// What the global grids' padding covers (m): options.reach_m or the ring's reach, whichever
/// is larger; throws gridloc::Error for a bad reach_m or a reach of a million cells or more.
double padding_reach(const CorrelationOptions& options, const SonarRing& ring) {
  require_option(options.reach_m >= 0.0 && std::isfinite(options.reach_m), "correlation options",
                 "reach_m", options.reach_m, "must be >= 0");
  const double reach = std::max(options.reach_m, ring.sonars.empty() ? 0.0 : ring.reach());
  if (reach / options.resolution > 1e6) {  // the padding alone would be 2 million cells wide
    std::ostringstream m;
    m << "correlation options: reach " << reach << " m is more than a million cells of "
      << options.resolution << " m; a sensor reaches metres, not kilometres";
    throw Error(m.str());
  }
  return reach;
}

/// Checks rigid scan points: alone in the observation, finite, some beam ends, within `reach`.
void check_points(const Observation& observation, double reach) {
  if (!observation.ranges.empty() || observation.scan || observation.ring ||
      !observation.rejected.empty()) {
    throw Error("observation: give scan points alone (no ranges, scan, ring or rejection mask)");
  }
  const ScanPoints& points = *observation.points;
  if (points.x.size() != points.size() || points.y.size() != points.size() ||
      points.norm.size() != points.size()) {
    throw Error("observation: scan points: x, y, norm and weight differ in length");
  }
  if (points.hit_count == 0 || points.hit_count > points.size()) {
    throw Error("observation: scan points have no beam end (nothing to match)");
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!std::isfinite(points.x[k]) || !std::isfinite(points.y[k]) ||
        !std::isfinite(points.weight[k])) {
      throw Error("observation: scan point " + std::to_string(k) + " is not finite");
    }
  }
  if (!(points.max_norm <= reach + 1e-9)) {
    std::ostringstream m;
    m << "observation: scan points reach " << points.max_norm << " m, beyond the estimator's reach "
      << reach << " m (set CorrelationOptions::reach_m)";
    throw Error(m.str());
  }
}

/// Checks that the observation is sonar readings for `ring` or a scan within `reach`, not
/// both; throws gridloc::Error naming what is wrong.
void check_observation(const Observation& observation, const SonarRing& ring, double reach) {
  if (observation.points) {
    check_points(observation, reach);
  } else if (observation.scan) {
    if (!observation.ranges.empty()) {
      throw Error("observation: give sonar ranges or a scan, not both");
    }
    if (!observation.rejected.empty()) {
      throw Error("observation: a rejection mask is for sonar readings, not for a scan");
    }
    if (observation.ring) throw Error("observation: a ring is for sonar readings, not for a scan");
    validate(*observation.scan);
    if (observation.scan->max_range > reach + 1e-9) {
      std::ostringstream m;
      m << "scan: max range " << observation.scan->max_range << " m exceeds the estimator's reach "
        << reach << " m (set CorrelationOptions::reach_m)";
      throw Error(m.str());
    }
  } else if (observation.ring) {
    if (ring.sonars.empty())
      throw Error("observation: this estimator has no sonar ring; give a scan");
    validate(*observation.ring);
    if (observation.ring->reach() > reach + 1e-9) {
      std::ostringstream m;
      m << "observation: the drive's ring reaches " << observation.ring->reach()
        << " m, beyond the estimator's reach " << reach
        << " m (set CorrelationOptions::reach_m to the ring's reach plus the drive's length)";
      throw Error(m.str());
    }
    validate_readings(*observation.ring, observation.ranges, observation.rejected);
  } else {
    if (ring.sonars.empty())
      throw Error("observation: this estimator has no sonar ring; give a scan");
    validate_readings(ring, observation.ranges, observation.rejected);
  }
}

}  // namespace correlation_detail

using namespace correlation_detail;

void validate(const SearchWindow& w) {
  auto bad = [](const char* field, double v, const char* rule) {
    require_option(false, "search window", field, v, rule);
  };
  if (!std::isfinite(w.center.x) || !std::isfinite(w.center.y) || !std::isfinite(w.center.theta)) {
    throw Error("search window: the prior pose must be finite");
  }
  if (!(w.half_xy >= 0.0) || !std::isfinite(w.half_xy)) bad("half_xy", w.half_xy, "must be >= 0");
  if (!(w.half_theta >= 0.0) || !(w.half_theta <= std::numbers::pi)) {
    bad("half_theta", w.half_theta, "must lie in [0, pi]");
  }
  if (!(w.step_xy > 0.0) || !std::isfinite(w.step_xy)) bad("step_xy", w.step_xy, "must be > 0");
  // More than a turn is no step (issue 14: --step-theta 1e300 drew a heatmap for minutes).
  if (!(w.step_theta > 0.0) || !(w.step_theta <= 2.0 * std::numbers::pi)) {
    bad("step_theta", w.step_theta, "must lie in (0, 2 pi]");
  }
}

Lattice CorrelationEstimator::lattice(const Observation& observation,
                                      const SearchWindow& window) const {
  check_observation(observation, ring_, reach_);
  validate(window);
  const double res = options_.resolution;
  if (std::abs(window.step_xy - res) > 1e-9) {
    std::ostringstream m;
    m << "search window: step_xy = " << window.step_xy << " must equal the estimator's grid "
      << "resolution " << res << " (the translation lattice is the grid)";
    throw Error(m.str());
  }

  const PaddedGrid& finest = levels_.front();
  const Pose2 prior = map_.geometry.to_grid_frame(window.center);
  const Cell c = {static_cast<int>(std::floor(prior.x / res)),
                  static_cast<int>(std::floor(prior.y / res))};
  if (c.ix < 0 || c.iy < 0 || c.ix >= finest.width || c.iy >= finest.height) {
    std::ostringstream m;
    m << "prior (" << window.center.x << ", " << window.center.y << ") lies outside the map";
    throw Error(m.str());
  }
  // The largest sensible window is global_window's: the whole map.
  const double map_w = finest.width * res, map_h = finest.height * res;
  if (window.half_xy > 0.5 * std::max(map_w, map_h) + res + 1e-9) {
    std::ostringstream m;
    m << "search window: +-" << window.half_xy << " m is larger than the map (" << map_w << " x "
      << map_h << " m); search the whole map with global localization (global_window, "
      << "gridloc localize --global)";
    throw Error(m.str());
  }
  // Clipped to the map below; the cap only keeps the integer arithmetic safe.
  const int n = static_cast<int>(std::min(std::lround(window.half_xy / res), 1L << 20));
  const double half_headings = window.half_theta / window.step_theta;
  if (half_headings > 50000.0) {
    std::ostringstream m;
    m << "search window: half_theta / step_theta = " << half_headings
      << " would search more than 100001 headings; use a larger step_theta";
    throw Error(m.str());
  }
  const int nt = static_cast<int>(std::lround(half_headings));
  Lattice lattice;
  lattice.x0 = std::max(0, c.ix - n);
  lattice.x1 = std::min(finest.width - 1, c.ix + n);
  lattice.y0 = std::max(0, c.iy - n);
  lattice.y1 = std::min(finest.height - 1, c.iy + n);
  lattice.headings = 2 * nt + 1;
  lattice.theta0 = prior.theta - nt * window.step_theta;
  lattice.step_theta = window.step_theta;
  return lattice;
}

namespace {

/// The farthest beam end of a scan or of rigid scan points (m).
double farthest_return(const Observation& observation) {
  double far = 0.0;
  if (observation.points) {
    const ScanPoints& points = *observation.points;
    for (std::size_t k = 0; k < points.hit_count; ++k) far = std::max(far, points.norm[k]);
  } else {
    for (double r : observation.scan->ranges) {
      if (r < observation.scan->max_range) far = std::max(far, r);
    }
  }
  return far;
}

}  // namespace

SearchWindow CorrelationEstimator::global_window(const Observation& observation) const {
  const PaddedGrid& finest = levels_.front();
  const double res = options_.resolution;
  SearchWindow w;
  w.step_xy = res;
  w.center =
      map_.geometry.to_world_frame({0.5 * finest.width * res, 0.5 * finest.height * res, 0.0});
  // Half the larger side plus a cell: the lattice covers every cell (it is clipped to the map).
  w.half_xy = 0.5 * std::max(finest.width, finest.height) * res + res;
  w.half_theta = std::numbers::pi;  // headings -pi and +pi coincide: one heading scored twice
  w.step_theta = deg2rad(5.0);
  if (observation.scan || observation.points) {
    const double far = farthest_return(observation);
    if (far > res) {
      const double step = std::acos(1.0 - res * res / (2.0 * far * far));
      w.step_theta = std::clamp(step, deg2rad(0.1), deg2rad(5.0));
    }
  }
  return w;
}

}  // namespace gridloc
