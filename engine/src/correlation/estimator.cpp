#include "gridloc/engine/correlation/estimator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <tuple>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {
namespace {

double level_resolution(double finest, int l) {
  return finest * static_cast<double>(1 << l);
}

/// The neighbourhood of `p` whose poses are not distinct from it: within distinct_xy and
/// distinct_theta, in lattice units (one definition for every strategy, so that they agree
/// exactly on the second peak).
Exclusion neighbourhood(const LatticePose& p, double res, double step_theta,
                        const CorrelationOptions& options) {
  return {p, options.distinct_xy / res,
          static_cast<int>(std::floor(options.distinct_theta / step_theta + 1e-9))};
}

/// Distinct local maxima of the scored poses: best first (ties to the lowest index), each
/// outside the neighbourhood of every one chosen before.
std::vector<LatticePose> distinct_peaks(std::vector<LatticePose> scored, double res,
                                        double step_theta, const CorrelationOptions& options,
                                        std::size_t max_count) {
  std::stable_sort(scored.begin(), scored.end(),
                   [](const LatticePose& a, const LatticePose& b) { return a.score > b.score; });
  std::vector<LatticePose> peaks;
  for (const auto& c : scored) {
    const bool distinct = std::none_of(peaks.begin(), peaks.end(), [&](const LatticePose& p) {
      return neighbourhood(p, res, step_theta, options).contains(c.ix, c.iy, c.it);
    });
    if (distinct) peaks.push_back(c);
    if (peaks.size() == max_count) break;
  }
  return peaks;
}

/// Covariance of the pose around the lattice winner `best`: every lattice pose within k
/// cells and k heading steps is scored, and read as a likelihood p ∝ exp(S - S_best) (the
/// score as a log-likelihood: one nat per fully matched unit-weight cell, the reading of a
/// correlation score real-time correlative matching uses); the weighted covariance of
/// (x, y, theta) plus the lattice's own quantization variance (step^2 / 12 per axis), rotated
/// into the world frame by the map's yaw.
Eigen::Matrix3d peak_covariance(const LatticePose& best, const Lattice& lattice,
                                const PaddedGrid& global,
                                const std::function<PlacedLocalGrid(int)>& placed_at, int k,
                                double yaw) {
  const double res = global.grid.geometry.resolution;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  double total = 0.0;
  // A lattice that goes all the way round wraps: the neighbours of heading 0 include the last.
  const bool round = lattice.headings * std::abs(lattice.step_theta) >= 2.0 * std::numbers::pi;
  const int t0 = round ? best.it - k : std::max(0, best.it - k);
  const int t1 = round ? best.it + k : std::min(lattice.headings - 1, best.it + k);
  for (int t = t0; t <= t1; ++t) {
    const int it = (t % lattice.headings + lattice.headings) % lattice.headings;
    const PlacedLocalGrid placed = placed_at(it);
    for (int iy = std::max(lattice.y0, best.iy - k); iy <= std::min(lattice.y1, best.iy + k);
         ++iy) {
      for (int ix = std::max(lattice.x0, best.ix - k); ix <= std::min(lattice.x1, best.ix + k);
           ++ix) {
        const double w = std::exp(std::min(0.0, score(global, placed, ix, iy) - best.score));
        // Offsets from the winner: metres, metres, radians.
        const Eigen::Vector3d d((ix - best.ix) * res, (iy - best.iy) * res,
                                (t - best.it) * lattice.step_theta);
        total += w;
        mean += w * d;
        second += w * d * d.transpose();
      }
    }
  }
  mean /= total;
  Eigen::Matrix3d cov = second / total - mean * mean.transpose();
  cov(0, 0) += res * res / 12.0;
  cov(1, 1) += res * res / 12.0;
  cov(2, 2) += lattice.step_theta * lattice.step_theta / 12.0;
  Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();  // grid frame -> world frame
  rotate.topLeftCorner<2, 2>() << std::cos(yaw), -std::sin(yaw), std::sin(yaw), std::cos(yaw);
  return rotate * cov * rotate.transpose();
}

/// Fills the confidence, its parts, the ambiguity flag and the verdict of `e` (README,
/// "Knowing when it is wrong"). `searched_second`: a distinct hypothesis was looked for.
void judge(Estimate& e, bool searched_second, const VerdictOptions& v) {
  ConfidenceParts& c = e.confidence_parts;
  c.fit = std::clamp(e.normalized_score, 0.0, 1.0);
  c.agreement = std::isnan(e.agreement) ? 1.0 : e.agreement;
  const double distinct =
      e.score > 0.0 ? std::clamp((e.score - e.second_score) / e.score, 0.0, 1.0) : 0.0;
  c.distinctness = searched_second ? distinct / (distinct + v.distinct_scale) : 1.0;
  const double spread = std::sqrt(std::max(0.0, e.covariance(0, 0) + e.covariance(1, 1)));
  c.sharpness = std::exp(-spread / v.spread_scale_m);
  e.confidence = c.agreement * c.fit * c.distinctness * c.sharpness;
  e.ambiguous = false;
  for (std::size_t k = 1; k < e.alternatives.size(); ++k) {
    const Hypothesis& h = e.alternatives[k];
    const double far = std::hypot(h.pose.x - e.lattice_pose.x, h.pose.y - e.lattice_pose.y);
    const double turn = std::abs(normalize_angle(h.pose.theta - e.lattice_pose.theta));
    if (h.score >= v.ambiguity_ratio * e.score && e.score > 0.0 &&
        (far > v.ambiguity_xy || turn > v.ambiguity_theta)) {
      e.ambiguous = true;
    }
  }
  e.verdict = e.ambiguous                              ? Verdict::Ambiguous
              : e.confidence >= v.localized_confidence ? Verdict::Localized
                                                       : Verdict::NotLocalized;
}

/// Estimate::agreement: the share of `ranges` that a noise-free simulation on `map` at
/// `pose` reproduces within 10 cm + 5 % (or both without echo); sonars flagged in `rejected`
/// are left out.
double reading_agreement(const OccupancyMap& map, const SonarRing& ring,
                         const std::vector<double>& ranges, const std::vector<bool>& rejected,
                         const Pose2& pose) {
  const std::vector<double> expected = simulate_sonar(map, ring, pose);
  int agree = 0, used = 0;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (i < rejected.size() && rejected[i]) continue;
    ++used;
    const double limit = ring.sonars[i].max_range;
    const bool none = ranges[i] >= limit, none_expected = expected[i] >= limit;
    if (none && none_expected) {
      ++agree;
    } else if (!none && !none_expected &&
               std::abs(ranges[i] - expected[i]) <= 0.10 + 0.05 * expected[i]) {
      ++agree;
    }
  }
  return used == 0 ? 0.0 : static_cast<double>(agree) / static_cast<double>(used);
}

/// Checks the options on their own; throws gridloc::Error naming the first that is wrong.
void check(const CorrelationOptions& options) {
  if (!(options.resolution > 0.0) || !std::isfinite(options.resolution)) {
    throw Error("correlation options: resolution must be > 0, got " +
                std::to_string(options.resolution));
  }
  if (options.levels < 1 || options.levels > 8) {
    throw Error("correlation options: levels must be in [1, 8], got " +
                std::to_string(options.levels));
  }
  if (options.keep < 1) throw Error("correlation options: keep must be >= 1");
  if (options.hypotheses < 1 || options.hypotheses > 100) {
    throw Error("correlation options: hypotheses must be in [1, 100], got " +
                std::to_string(options.hypotheses));
  }
  if (options.covariance_cells < 0 || options.covariance_cells > 20) {
    throw Error("correlation options: covariance_cells must be in [0, 20], got " +
                std::to_string(options.covariance_cells));
  }
  validate(options.scan);
  if (!(options.budget_ms >= 0.0) || !std::isfinite(options.budget_ms)) {
    throw Error("correlation options: budget_ms must be finite and >= 0, got " +
                std::to_string(options.budget_ms));
  }
  // Options only branch and bound can honour are errors elsewhere, not silently ignored.
  if (options.strategy != SearchStrategy::BranchAndBound &&
      (options.budget_ms > 0.0 || options.heading_intervals)) {
    throw Error(std::string("correlation options: ") +
                (options.budget_ms > 0.0 ? "budget_ms" : "heading_intervals") +
                " needs the branch-and-bound strategy");
  }
  if (options.threads < 1 || options.threads > 256) {
    throw Error("correlation options: threads must be in [1, 256], got " +
                std::to_string(options.threads));
  }
}

/// What the global grids' padding covers (m): options.reach_m or the ring's reach, whichever
/// is larger; throws gridloc::Error for a bad reach_m or a reach of a million cells or more.
double padding_reach(const CorrelationOptions& options, const SonarRing& ring) {
  if (!(options.reach_m >= 0.0) || !std::isfinite(options.reach_m)) {
    throw Error("correlation options: reach_m must be >= 0, got " +
                std::to_string(options.reach_m));
  }
  const double reach = std::max(options.reach_m, ring.sonars.empty() ? 0.0 : ring.reach());
  if (reach / options.resolution > 1e6) {  // the padding alone would be 2 million cells wide
    std::ostringstream m;
    m << "correlation options: reach " << reach << " m is more than a million cells of "
      << options.resolution << " m; a sensor reaches metres, not kilometres";
    throw Error(m.str());
  }
  return reach;
}

/// Checks that the observation is sonar readings for `ring` or a scan within `reach`, not
/// both; throws gridloc::Error naming what is wrong.
void check_observation(const Observation& observation, const SonarRing& ring, double reach) {
  if (observation.scan) {
    if (!observation.ranges.empty()) {
      throw Error("observation: give sonar ranges or a scan, not both");
    }
    if (!observation.rejected.empty()) {
      throw Error("observation: a rejection mask is for sonar readings, not for a scan");
    }
    validate(*observation.scan);
    if (observation.scan->max_range > reach + 1e-9) {
      std::ostringstream m;
      m << "scan: max range " << observation.scan->max_range << " m exceeds the estimator's reach "
        << reach << " m (set CorrelationOptions::reach_m)";
      throw Error(m.str());
    }
  } else {
    if (ring.sonars.empty())
      throw Error("observation: this estimator has no sonar ring; give a scan");
    validate_readings(ring, observation.ranges, observation.rejected);
  }
}

/// A scan's points under a point model, made once and rotated per heading; nullopt for
/// sonar readings and for ray-model scans.
std::optional<ScanPoints> rigid_points(const Observation& observation,
                                       const ScanModelOptions& scan) {
  if (observation.scan && scan.model != ScanModel::Rays) {
    return scan_points(*observation.scan, scan);
  }
  return std::nullopt;
}

/// Milliseconds since `start`.
double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// World pose of lattice coordinates (fractions allowed): the cell's centre, the heading.
Pose2 lattice_to_world(const GridGeometry& geometry, const Lattice& lattice, double res, double ix,
                       double iy, double it) {
  return geometry.to_world_frame({(ix + 0.5) * res, (iy + 0.5) * res, lattice.theta(it)});
}

/// One estimate()'s search of its lattice, shared by the steps after it: the levels searched,
/// the branch-and-bound heading grids (made by the first search, reused by the next
/// hypotheses, the refinement and the covariance) and options, and what the searches found.
struct WindowSearch {
  WindowSearch(const Lattice& searched, const std::vector<SearchLevel>& search_levels,
               const BoundPyramid& bound_pyramid)
      : lattice(searched), levels(search_levels), pyramid(bound_pyramid) {}
  const SearchLevel& finest() const { return levels.front(); }

  const Lattice& lattice;
  const std::vector<SearchLevel>& levels;
  const BoundPyramid& pyramid;        ///< of the finest level's grid (branch and bound)
  std::optional<HeadingGrids> grids;  ///< branch and bound only
  BranchAndBoundOptions bnb;
  SearchResult result;  ///< of the first search, with the counters of all
};

/// The strategy's search for the best lattice pose (ties to the lowest index).
void search_lattice(WindowSearch& search, const CorrelationOptions& options) {
  search.bnb.threads = options.threads;
  search.bnb.budget_ms = options.budget_ms;
  search.bnb.heading_intervals = options.heading_intervals;
  switch (options.strategy) {
    case SearchStrategy::Exhaustive:
      search.result = search_exhaustive(search.lattice, search.finest());
      break;
    case SearchStrategy::Multires:
      search.result = search_multires(search.lattice, search.levels, options.keep);
      search.result.proven_optimal = false;
      search.result.upper_bound = std::numeric_limits<double>::quiet_NaN();
      break;
    case SearchStrategy::BranchAndBound:
      search.grids.emplace(search.lattice, search.finest());
      search.result =
          search_branch_and_bound(search.lattice, *search.grids, search.pyramid, search.bnb);
      break;
  }
}

/// Estimate::lattice_pose and Estimate::pose: the winner in the world, refined below a cell
/// and a heading step (refine()) when options.refine.
void place_winner(Estimate& e, const WindowSearch& search, const GridGeometry& geometry,
                  const CorrelationOptions& options) {
  const double res = options.resolution;
  const LatticePose& best = search.result.best;
  e.lattice_pose = lattice_to_world(geometry, search.lattice, res, best.ix, best.iy, best.it);
  e.pose = e.lattice_pose;
  if (options.refine) {
    // Branch and bound already built the lattice headings' grids: refinement reuses them.
    std::function<const PlacedLocalGrid*(int)> built;
    if (search.grids) built = [&](int it) { return &search.grids->placed(it); };
    const RefinedPose refined = refine(best, search.lattice, search.finest(), 4, built);
    e.pose = lattice_to_world(geometry, search.lattice, res, refined.ix, refined.iy, refined.it);
  }
}

/// Estimate::on_window_edge: `best` lies on an edge of the window as asked (not one where the
/// map clipped it), so a better pose may lie beyond it.
bool on_window_edge(const LatticePose& best, const Lattice& lattice, const SearchWindow& window,
                    const GridGeometry& geometry, double res) {
  const double span = 2.0 * window.half_xy / res;  // the unclipped window, in cells
  const Pose2 prior = geometry.to_grid_frame(window.center);
  const int cx = static_cast<int>(std::floor(prior.x / res));
  const int cy = static_cast<int>(std::floor(prior.y / res));
  const int n = static_cast<int>(std::lround(span / 2.0));
  const bool x_edge = (best.ix == lattice.x0 && lattice.x0 == cx - n) ||
                      (best.ix == lattice.x1 && lattice.x1 == cx + n);
  const bool y_edge = (best.iy == lattice.y0 && lattice.y0 == cy - n) ||
                      (best.iy == lattice.y1 && lattice.y1 == cy + n);
  const bool all_headings = lattice.headings * window.step_theta >= 2.0 * std::numbers::pi;
  const bool t_edge = !all_headings && (best.it == 0 || best.it == lattice.headings - 1);
  return x_edge || y_edge || t_edge;
}

/// The best pose of `seen` outside every zone of `exclude` (ties to the lowest index), if any.
std::optional<LatticePose> best_outside(const std::vector<LatticePose>& seen,
                                        const std::vector<Exclusion>& exclude) {
  std::optional<LatticePose> best;
  for (const auto& p : seen) {
    const bool excluded = std::any_of(exclude.begin(), exclude.end(), [&](const Exclusion& z) {
      return z.contains(p.ix, p.iy, p.it);
    });
    if (!excluded && (!best || better(p, *best))) best = p;
  }
  return best;
}

/// The hypotheses of branch and bound, which scores few poses: each next distinct pose is
/// found exactly, by a search that leaves out the neighbourhoods of those found, starting from
/// the best pose outside them that an earlier search scored (the greedy order of
/// distinct_peaks). Later searches get what is left of options.budget_ms since `start`.
std::vector<LatticePose> exact_hypotheses(WindowSearch& search, const CorrelationOptions& options,
                                          std::chrono::steady_clock::time_point start) {
  const auto wanted = static_cast<std::size_t>(options.hypotheses);
  BranchAndBoundOptions& bnb = search.bnb;
  SearchResult& result = search.result;
  std::vector<LatticePose> peaks{result.best};
  std::vector<LatticePose> seen = result.scored;
  while (peaks.size() < wanted) {
    bnb.exclude.push_back(
        neighbourhood(peaks.back(), options.resolution, search.lattice.step_theta, options));
    bnb.incumbent = best_outside(seen, bnb.exclude);
    SearchResult next;
    next.best = bnb.incumbent.value_or(LatticePose{});
    if (options.budget_ms > 0.0) bnb.budget_ms = options.budget_ms - elapsed_ms(start);
    if (options.second_peak && (options.budget_ms <= 0.0 || bnb.budget_ms > 0.0)) {
      next = search_branch_and_bound(search.lattice, *search.grids, search.pyramid, bnb);
      seen.insert(seen.end(), next.scored.begin(), next.scored.end());
      result.poses_scored += next.poses_scored;
      result.cells_scored += next.cells_scored;
    }
    if (!bnb.incumbent && next.poses_scored == 0) break;  // every other pose is excluded
    peaks.push_back(next.best);
  }
  return peaks;
}

/// Estimate::alternatives as lattice poses: up to options.hypotheses distinct ones, the
/// winner first.
std::vector<LatticePose> hypotheses(WindowSearch& search, const CorrelationOptions& options,
                                    std::chrono::steady_clock::time_point start) {
  if (options.strategy == SearchStrategy::BranchAndBound) {
    return exact_hypotheses(search, options, start);
  }
  return distinct_peaks(search.result.scored, options.resolution, search.lattice.step_theta,
                        options, static_cast<std::size_t>(options.hypotheses));
}

/// peak_covariance() of the winner within `cells`, reusing branch and bound's heading grids.
Eigen::Matrix3d winner_covariance(const WindowSearch& search, int cells, double yaw) {
  std::function<PlacedLocalGrid(int)> placed_at = [&](int it) {
    return search.grids ? search.grids->placed(it)
                        : place_heading(search.finest(), search.lattice.theta(it));
  };
  return peak_covariance(search.result.best, search.lattice, *search.finest().global, placed_at,
                         cells, yaw);
}

/// Estimate::stats of the searches, timed since `start`.
void fill_stats(Estimate& e, const SearchResult& result, int levels,
                std::chrono::steady_clock::time_point start) {
  e.stats.poses_scored = result.poses_scored;
  e.stats.cells_scored = result.cells_scored;
  e.stats.levels = levels;
  e.stats.proven_optimal = result.proven_optimal;
  e.stats.upper_bound = result.upper_bound;
  e.stats.elapsed_ms = elapsed_ms(start);
}

}  // namespace

std::string to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Localized:
      return "localized";
    case Verdict::Ambiguous:
      return "ambiguous";
    case Verdict::NotLocalized:
      return "not localized";
  }
  return "unknown";
}

std::string to_string(SearchStrategy strategy) {
  switch (strategy) {
    case SearchStrategy::BranchAndBound:
      return "bnb";
    case SearchStrategy::Exhaustive:
      return "exhaustive";
    case SearchStrategy::Multires:
      return "multires";
  }
  return "unknown";
}

void validate(const SearchWindow& w) {
  auto bad = [](const std::string& field, double v, const std::string& rule) {
    std::ostringstream m;
    m << "search window: " << field << " = " << v << " " << rule;
    throw Error(m.str());
  };
  if (!std::isfinite(w.center.x) || !std::isfinite(w.center.y) || !std::isfinite(w.center.theta)) {
    throw Error("search window: the prior pose must be finite");
  }
  if (!(w.half_xy >= 0.0) || !std::isfinite(w.half_xy)) bad("half_xy", w.half_xy, "must be >= 0");
  if (!(w.half_theta >= 0.0) || !(w.half_theta <= std::numbers::pi)) {
    bad("half_theta", w.half_theta, "must lie in [0, pi]");
  }
  if (!(w.step_xy > 0.0) || !std::isfinite(w.step_xy)) bad("step_xy", w.step_xy, "must be > 0");
  if (!(w.step_theta > 0.0) || !std::isfinite(w.step_theta)) {
    bad("step_theta", w.step_theta, "must be > 0");
  }
}

CorrelationEstimator::CorrelationEstimator(OccupancyMap map, SonarRing ring,
                                           CorrelationOptions options)
    : map_(std::move(map)), ring_(std::move(ring)), options_(options) {
  if (!ring_.sonars.empty() || options_.reach_m <= 0.0) validate(ring_);
  check(options_);
  if (map_.cells.empty()) throw Error("correlation estimator: the map is empty");
  reach_ = padding_reach(options_, ring_);
  // Only the multiresolution search reads the coarser levels.
  const int built = options_.strategy == SearchStrategy::Multires ? options_.levels : 1;
  for (int l = 0; l < built; ++l) {
    const double res = level_resolution(options_.resolution, l);
    const int pad = static_cast<int>(std::ceil(reach_ / res)) + 3;
    levels_.push_back(
        pad_grid(make_global_grid(map_, res, options_.global), pad, options_.arc_rule));
  }
  if (options_.strategy == SearchStrategy::BranchAndBound) {
    // Deep enough for a window over the whole map; small windows start lower.
    const PaddedGrid& finest = levels_.front();
    int depth = 0;
    while ((1 << depth) < std::max(finest.width, finest.height)) ++depth;
    ++depth;  // heading intervals widen blocks up to twice their side
    pyramid_ = make_bound_pyramid(finest, depth);
  }
}

CorrelationEstimator::CorrelationEstimator(OccupancyMap map, CorrelationOptions options)
    : CorrelationEstimator(std::move(map), SonarRing{}, options) {}

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

Estimate CorrelationEstimator::estimate(const Observation& observation,
                                        const SearchWindow& window) const {
  const auto start = std::chrono::steady_clock::now();
  const Lattice lattice = this->lattice(observation, window);  // checks both first
  const std::optional<ScanPoints> points = rigid_points(observation, options_.scan);
  const int level_count = options_.strategy == SearchStrategy::Multires ? options_.levels : 1;
  const std::vector<SearchLevel> levels =
      search_levels(observation, points ? &*points : nullptr, level_count);
  WindowSearch search(lattice, levels, pyramid_);
  search_lattice(search, options_);
  const LatticePose& best = search.result.best;

  Estimate e;
  place_winner(e, search, map_.geometry, options_);
  e.score = best.score;
  e.agreement = observation.scan ? std::numeric_limits<double>::quiet_NaN()
                                 : reading_agreement(map_, ring_, observation.ranges,
                                                     observation.rejected, e.pose);
  e.on_window_edge = on_window_edge(best, lattice, window, map_.geometry, options_.resolution);
  // The winning heading's local grid: the most any pose could score.
  const double mass =
      levels.front().make_local(lattice.theta(best.it), Eigen::Vector2d::Zero()).mass();
  e.normalized_score = mass > 0.0 ? e.score / mass : 0.0;
  const std::vector<LatticePose> peaks = hypotheses(search, options_, start);
  e.second_score = peaks.size() > 1 ? peaks[1].score : e.score;
  for (const auto& p : peaks) {
    e.alternatives.push_back(
        {lattice_to_world(map_.geometry, lattice, options_.resolution, p.ix, p.iy, p.it), p.score});
  }
  if (options_.covariance_cells > 0) {
    e.covariance = winner_covariance(search, options_.covariance_cells, map_.geometry.yaw);
  }
  judge(e, peaks.size() > 1, options_.verdict);
  fill_stats(e, search.result, level_count, start);
  return e;
}

std::vector<SearchLevel> CorrelationEstimator::search_levels(const Observation& observation,
                                                             const ScanPoints* points,
                                                             int count) const {
  std::vector<SearchLevel> levels;
  for (int l = 0; l < count; ++l) {
    levels.push_back(
        {&levels_[static_cast<std::size_t>(l)],
         [this, &observation, points, level_res = level_resolution(options_.resolution, l)](
             double theta, const Eigen::Vector2d& centre) {
           return local_grid(observation, points, theta, level_res, centre);
         },
         options_.threads});
  }
  // Rigid points: branch and bound places them directly and can bound heading intervals.
  if (points != nullptr) levels.front().points = points;
  return levels;
}

ScoreVolume CorrelationEstimator::score_volume(const Observation& observation,
                                               const SearchWindow& window) const {
  const Lattice lattice = this->lattice(observation, window);
  const double res = options_.resolution;
  const std::optional<ScanPoints> points = rigid_points(observation, options_.scan);
  const SearchLevel level = search_levels(observation, points ? &*points : nullptr, 1).front();
  const SearchResult r = search_exhaustive(lattice, level);
  ScoreVolume v;
  v.nx = lattice.x1 - lattice.x0 + 1;
  v.ny = lattice.y1 - lattice.y0 + 1;
  v.headings = lattice.headings;
  v.ix0 = lattice.x0;
  v.iy0 = lattice.y0;
  v.resolution = res;
  v.theta0 = lattice.theta0;
  v.step_theta = lattice.step_theta;
  v.geometry = levels_.front().grid.geometry;  // the finest grid: resolution, origin, yaw
  v.geometry.width = levels_.front().width;
  v.geometry.height = levels_.front().height;
  v.scores.assign(static_cast<std::size_t>(v.nx) * v.ny * v.headings, 0.0);
  for (const LatticePose& p : r.scored) {
    v.scores[v.index(p.ix - v.ix0, p.iy - v.iy0, p.it)] = p.score;
  }
  v.best = {r.best.ix - v.ix0, r.best.iy - v.iy0, r.best.it, r.best.score};
  v.mass.resize(static_cast<std::size_t>(v.headings));
  for (int it = 0; it < v.headings; ++it) {
    v.mass[static_cast<std::size_t>(it)] =
        level.make_local(lattice.theta(it), Eigen::Vector2d::Zero()).mass();
  }
  return v;
}

Pose2 ScoreVolume::pose(double x, double y, double t) const {
  return geometry.to_world_frame(
      {(ix0 + x + 0.5) * resolution, (iy0 + y + 0.5) * resolution, theta0 + t * step_theta});
}

SparseLocalGrid CorrelationEstimator::local_grid(const Observation& observation,
                                                 const ScanPoints* points, double theta,
                                                 double resolution,
                                                 const Eigen::Vector2d& centre) const {
  // A scan is oriented by construction; the sonar ring follows options.local.
  if (points != nullptr) return rasterize_points(*points, theta, resolution, centre);
  if (observation.scan) {
    return rasterize_scan(*observation.scan, theta, resolution, centre, options_.scan);
  }
  return rasterize(ring_, observation.ranges, theta, resolution, options_.local, centre,
                   options_.sonar, observation.rejected);
}

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
  if (observation.scan) {
    double far = 0.0;
    for (double r : observation.scan->ranges) {
      if (r < observation.scan->max_range) far = std::max(far, r);
    }
    if (far > res) {
      const double step = std::acos(1.0 - res * res / (2.0 * far * far));
      w.step_theta = std::clamp(step, deg2rad(0.1), deg2rad(5.0));
    }
  }
  return w;
}

}  // namespace gridloc
