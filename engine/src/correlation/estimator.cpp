// The correlation estimator: its grids, the strategies' search of a window's lattice, the
// hypotheses, and the estimate and score volume they give.
#include "gridloc/engine/correlation/estimator.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "checks.hpp"
#include "confidence.hpp"
#include "gridloc/grids/error.hpp"
#include "prepared_search.hpp"

namespace gridloc {

using namespace correlation_detail;
namespace {

double level_resolution(double finest, int l) {
  return finest * static_cast<double>(1 << l);
}

/// A scan's points under a point model (or the observation's own points), made once and
/// rotated per heading; nullopt for sonar readings and for ray-model scans.
std::optional<ScanPoints> rigid_points(const Observation& observation,
                                       const ScanModelOptions& scan) {
  if (observation.points) return observation.points;
  if (observation.scan && scan.model != ScanModel::Rays) {
    return scan_points(*observation.scan, scan);
  }
  return std::nullopt;
}

/// The size of a search of `lattice` on `finest`, for its memory check: one heading's local
/// grid is made to count its cells (a rigid scan's points are counted as they are). An
/// exhaustive or multiresolution search (`strategy`) keeps the poses it scores (Multires
/// every pose of its coarsest level), a score volume (`volume`) every pose.
SearchSize search_size(const Lattice& lattice, const SearchLevel& finest, SearchStrategy strategy,
                       int levels, bool volume) {
  SearchSize size;
  size.translations = static_cast<double>(lattice.x1 - lattice.x0 + 1) *
                      static_cast<double>(lattice.y1 - lattice.y0 + 1);
  size.headings = lattice.headings;
  if (finest.points != nullptr) {
    size.local_cells = size.point_cells = static_cast<double>(finest.points->size());
  } else {
    size.local_cells =
        static_cast<double>(finest.make_local(lattice.theta(0), Eigen::Vector2d::Zero()).size());
  }
  size.every_pose = volume || strategy != SearchStrategy::BranchAndBound;
  if (!volume && strategy == SearchStrategy::Multires) {
    size.translations /= std::pow(4.0, levels - 1);
  }
  return size;
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

/// The threads a search of `lattice` runs on (CorrelationOptions::poses_per_thread).
int threads_for(const Lattice& lattice, const CorrelationOptions& options) {
  if (options.poses_per_thread <= 0.0 || options.threads <= 1) return options.threads;
  const double poses = static_cast<double>(lattice.x1 - lattice.x0 + 1) *
                       static_cast<double>(lattice.y1 - lattice.y0 + 1) * lattice.headings;
  const double share = std::floor(poses / options.poses_per_thread);
  return static_cast<int>(std::clamp(share, 1.0, static_cast<double>(options.threads)));
}

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
    const LatticePose start =
        centre_of_heading_ties(best, search.lattice, search.finest(), 8, built);
    const RefinedPose refined = refine(start, search.lattice, search.finest(), 4, built);
    e.pose = lattice_to_world(geometry, search.lattice, res, refined.ix, refined.iy, refined.it);
  }
}

/// The edges of the window `best` lies on, as asked (not where the map clipped it), per axis
/// (x, y, heading): kLowEdge, kHighEdge, both (a window one step wide) or 0; no heading edge
/// when the window covers every heading.
constexpr int kLowEdge = 1, kHighEdge = 2;
std::array<int, 3> window_edge_sides(const LatticePose& best, const Lattice& lattice,
                                     const SearchWindow& window, const GridGeometry& geometry,
                                     double res) {
  const double span = 2.0 * window.half_xy / res;  // the unclipped window, in cells
  const Pose2 prior = geometry.to_grid_frame(window.center);
  const int cx = static_cast<int>(std::floor(prior.x / res));
  const int cy = static_cast<int>(std::floor(prior.y / res));
  const int n = static_cast<int>(std::lround(span / 2.0));
  const auto side = [](bool low, bool high) {
    return (low ? kLowEdge : 0) | (high ? kHighEdge : 0);
  };
  const bool all_headings = lattice.headings * window.step_theta >= 2.0 * std::numbers::pi;
  return {side(best.ix == lattice.x0 && lattice.x0 == cx - n,
               best.ix == lattice.x1 && lattice.x1 == cx + n),
          side(best.iy == lattice.y0 && lattice.y0 == cy - n,
               best.iy == lattice.y1 && lattice.y1 == cy + n),
          all_headings ? 0 : side(best.it == 0, best.it == lattice.headings - 1)};
}

/// `step` (-1, 0, +1 along one axis) when it leaves the window through an edge in `edges`
/// (window_edge_sides), else 0.
int step_out(int step, int edges) {
  const bool past = (step < 0 && (edges & kLowEdge)) || (step > 0 && (edges & kHighEdge));
  return past ? step : 0;
}

/// Estimate::rises_past_window_edge: a lattice pose next to the winner (its 26 neighbours,
/// diagonal ones too) past an edge of the window it lies on, and the pose one more step out
/// along the axes it crossed, both score above it (on the map). Two steps, since the lattice
/// may stop up to half a step short of the window asked for: a truth in that gap lifts the
/// first step out, not the second.
bool rises_past_edge(const WindowSearch& search, const std::array<int, 3>& sides) {
  const LatticePose& best = search.result.best;
  const PaddedGrid& global = *search.finest().global;
  // The lattice's headings reuse the search's grids; those past it are placed here, once.
  std::array<std::optional<PlacedLocalGrid>, 5> beyond;  // heading offsets -2 .. 2
  const auto placed_at = [&](int dt) -> const PlacedLocalGrid& {
    const int it = best.it + dt;
    if (search.grids && it >= 0 && it < search.lattice.headings) return search.grids->placed(it);
    std::optional<PlacedLocalGrid>& grid = beyond[static_cast<std::size_t>(dt + 2)];
    if (!grid) grid = place_heading(search.finest(), search.lattice.theta(it));
    return *grid;
  };
  const auto above = [&](int dx, int dy, int dt) {
    const int ix = best.ix + dx, iy = best.iy + dy;
    if (ix < 0 || iy < 0 || ix >= global.width || iy >= global.height) return false;
    return score(global, placed_at(dt), ix, iy) > best.score;
  };
  for (int dt = -1; dt <= 1; ++dt) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int out_x = step_out(dx, sides[0]), out_y = step_out(dy, sides[1]),
                  out_t = step_out(dt, sides[2]);
        if (out_x == 0 && out_y == 0 && out_t == 0) continue;
        if (above(dx, dy, dt) && above(dx + out_x, dy + out_y, dt + out_t)) return true;
      }
    }
  }
  return false;
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

/// The winner and the distinct hypotheses after it; `floor` set when the search for the
/// next one found no distinct pose scoring options.second_peak_floor of the winner or more
/// (then that share of its score is an upper bound of the next one's score).
struct Peaks {
  std::vector<LatticePose> poses;
  std::optional<double> floor;
};

/// The score below which branch and bound does not look for hypotheses after the winner.
double hypothesis_floor(const SearchResult& result, const CorrelationOptions& options) {
  return options.second_peak_floor > 0.0 && result.best.score > 0.0
             ? options.second_peak_floor * result.best.score
             : -std::numeric_limits<double>::infinity();
}

/// Whether branch and bound finds the hypotheses after the winner in its own search: it
/// keeps every node that could hold a pose scoring second_peak_floor of the incumbent
/// (BranchAndBoundOptions::keep_share), so the distinct peaks above the floor are among the
/// poses it scored. Not under a budget, which could stop the search before them, nor for a
/// sonar ring: its scores are flat, so that search kept most nodes (about 2 800 poses of
/// room_l's seed window against 76-196 for the best and then one more search; the same
/// peaks, 1.3-2.4x the time), where a laser's kept few.
bool hypotheses_in_one_pass(const CorrelationOptions& options, int hypotheses,
                            const Observation& observation) {
  const bool ring = !observation.scan && !observation.points;
  return options.strategy == SearchStrategy::BranchAndBound && options.second_peak &&
         hypotheses > 1 && options.second_peak_floor > 0.0 && options.budget_ms <= 0.0 && !ring;
}

/// The distinct peaks among the scored poses that reach the floor (all of them without
/// one), in the greedy order of distinct_peaks. The exhaustive search scored every pose, and
/// the one-pass branch and bound (hypotheses_in_one_pass) every pose reaching the floor, so
/// each peak is the exact best outside the ones before it. Fewer than wanted: the next one
/// scores less than the floor (or no pose is distinct from them; the floor bounds it too).
Peaks peaks_above_floor(const WindowSearch& search, const CorrelationOptions& options) {
  const double floor = hypothesis_floor(search.result, options);
  std::vector<LatticePose> above;
  for (const LatticePose& p : search.result.scored) {
    if (p.score >= floor) above.push_back(p);
  }
  const auto wanted = static_cast<std::size_t>(options.hypotheses);
  Peaks peaks{distinct_peaks(std::move(above), options.resolution, search.lattice, options, wanted),
              std::nullopt};
  if (peaks.poses.size() < wanted && std::isfinite(floor)) peaks.floor = floor;
  return peaks;
}

/// The hypotheses of branch and bound, which scores few poses: each next distinct pose is
/// found exactly, by a search that leaves out the neighbourhoods of those found, starting from
/// the best pose outside them that an earlier search scored (the greedy order of
/// distinct_peaks), and dropping what cannot reach the floor. Later searches get what is left
/// of options.budget_ms since `start`.
Peaks exact_hypotheses(WindowSearch& search, const CorrelationOptions& options,
                       std::chrono::steady_clock::time_point start) {
  const auto wanted = static_cast<std::size_t>(options.hypotheses);
  BranchAndBoundOptions& bnb = search.bnb;
  SearchResult& result = search.result;
  Peaks peaks{{result.best}, std::nullopt};
  std::vector<LatticePose> seen = result.scored;
  bnb.min_score = hypothesis_floor(result, options);
  while (peaks.poses.size() < wanted) {
    bnb.exclude.push_back(
        neighbourhood(peaks.poses.back(), options.resolution, search.lattice, options));
    bnb.incumbent = best_outside(seen, bnb.exclude);
    SearchResult next;
    next.best = bnb.incumbent.value_or(LatticePose{});
    if (options.budget_ms > 0.0) bnb.budget_ms = options.budget_ms - elapsed_ms(start);
    const bool searched = options.second_peak && (options.budget_ms <= 0.0 || bnb.budget_ms > 0.0);
    if (searched) {
      next = search_branch_and_bound(search.lattice, *search.grids, search.pyramid, bnb);
      seen.insert(seen.end(), next.scored.begin(), next.scored.end());
      result.poses_scored += next.poses_scored;
      result.cells_scored += next.cells_scored;
      if (!next.found || next.best.score < bnb.min_score) {  // none distinct reaches the floor
        peaks.floor = bnb.min_score;
        break;
      }
    }
    if (!bnb.incumbent && next.poses_scored == 0) break;  // every other pose is excluded
    peaks.poses.push_back(next.best);
  }
  return peaks;
}

/// Estimate::alternatives as lattice poses: up to options.hypotheses distinct ones, the
/// winner first.
Peaks this_many_hypotheses(WindowSearch& search, const CorrelationOptions& options,
                           const Observation& observation,
                           std::chrono::steady_clock::time_point start) {
  if (options.strategy == SearchStrategy::BranchAndBound &&
      !hypotheses_in_one_pass(options, options.hypotheses, observation)) {
    return exact_hypotheses(search, options, start);
  }
  return peaks_above_floor(search, options);
}

/// peak_covariance() of the winner within `cells`, reusing branch and bound's heading grids.
std::vector<Eigen::Matrix3d> winner_covariances(const WindowSearch& search, int cells, double yaw,
                                                const std::vector<double>& temperatures) {
  std::function<PlacedLocalGrid(int)> placed_at = [&](int it) {
    return search.grids ? search.grids->placed(it)
                        : place_heading(search.finest(), search.lattice.theta(it));
  };
  return peak_covariances(search.result.best, search.lattice, *search.finest().global, placed_at,
                          cells, yaw, temperatures);
}

/// The temperature of the covariance an observation's estimate reports.
double reported_temperature(const Observation& observation, const CorrelationOptions& options) {
  const bool ring = !observation.scan && !observation.points;
  return ring && options.ring_covariance_temperature > 0.0 ? options.ring_covariance_temperature
                                                           : options.covariance_temperature;
}

/// A scan's reported covariance with only scan_quantization_share of the lattice's
/// quantization variance (peak_covariances adds all of it) when its pose is refined.
void share_quantization(Eigen::Matrix3d& covariance, const Observation& observation,
                        const Lattice& lattice, const CorrelationOptions& options) {
  const bool ring = !observation.scan && !observation.points;
  if (!options.refine) return;
  const double drop =
      1.0 - (ring ? options.ring_quantization_share : options.scan_quantization_share);
  const double res = options.resolution;
  covariance(0, 0) -= drop * res * res / 12.0;  // isotropic in x, y: the map's yaw keeps it
  covariance(1, 1) -= drop * res * res / 12.0;
  covariance(2, 2) -= drop * lattice.step_theta * lattice.step_theta / 12.0;
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

int window_bound_depth(const SearchWindow& window) {
  const double half_cells = std::ceil(window.half_xy / window.step_xy);
  const double cells = 2.0 * half_cells + 1.0;
  int depth = 0;
  while (depth < 30 && std::ldexp(1.0, depth) < cells) ++depth;
  return depth + 1;  // heading intervals widen blocks up to twice their side
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

CorrelationEstimator::CorrelationEstimator(OccupancyMap map, SonarRing ring,
                                           CorrelationOptions options)
    : map_(std::move(map)), ring_(std::move(ring)), options_(options) {
  if (!ring_.sonars.empty() || options_.reach_m <= 0.0) validate(ring_);
  check(options_);
  if (map_.cells.empty()) throw Error("correlation estimator: the map is empty");
  reach_ = padding_reach(options_, ring_);
  // A laser's hits score only positive cells, as fixed point: no bound reads a min-pooled
  // level, and no score a float cell (an observation bringing its own ring still gets a
  // valid, looser bound, and the floats the int8 cells stand for).
  positive_only_ = ring_.sonars.empty() && options_.scan.model == ScanModel::Hits;
  check_resources(map_.geometry, options_, reach_, {}, positive_only_);  // before allocating
  // Only the multiresolution search reads the coarser levels.
  const int built = options_.strategy == SearchStrategy::Multires ? options_.levels : 1;
  for (int l = 0; l < built; ++l) {
    const double res = level_resolution(options_.resolution, l);
    const int pad = static_cast<int>(std::ceil(reach_ / res)) + 3;
    levels_.push_back(pad_grid(
        make_global_grid(map_, res, options_.global, options_.field, options_.limits), pad,
        options_.arc_rule, keeps_floats() ? PaddedCells::FloatsToo : PaddedCells::Int8WhereExact));
  }
  if (options_.strategy == SearchStrategy::BranchAndBound) {
    // Deep enough for a window over the whole map; small windows start lower.
    const PaddedGrid& finest = levels_.front();
    int depth = 0;
    while ((1 << depth) < std::max(finest.width, finest.height)) ++depth;
    ++depth;  // heading intervals widen blocks up to twice their side
    if (options_.max_bound_depth > 0) depth = std::min(depth, options_.max_bound_depth);
    pyramid_ = make_bound_pyramid(
        finest, depth, positive_only_ ? PyramidLevels::MaxOnly : PyramidLevels::MaxAndMin);
  }
}

CorrelationEstimator::CorrelationEstimator(OccupancyMap map, CorrelationOptions options)
    : CorrelationEstimator(std::move(map), SonarRing{}, options) {}

Estimate CorrelationEstimator::estimate(const Observation& observation,
                                        const SearchWindow& window) const {
  return estimate(observation, window, options_.hypotheses);
}

Estimate CorrelationEstimator::estimate(const Observation& observation, const SearchWindow& window,
                                        int hypotheses) const {
  PreparedSearch prepared;
  prepare(prepared, observation, window, hypotheses);
  search_lattice(*prepared.search, prepared.options);
  return conclude(prepared, observation, window);
}

void CorrelationEstimator::prepare(PreparedSearch& prepared, const Observation& observation,
                                   const SearchWindow& window, int hypotheses) const {
  if (hypotheses < 1) throw Error("estimate: hypotheses must be at least 1");
  prepared.start = std::chrono::steady_clock::now();
  prepared.options = options_;
  prepared.options.hypotheses = hypotheses;
  prepared.lattice = this->lattice(observation, window);  // checks both first
  prepared.options.threads = threads_for(prepared.lattice, options_);
  prepared.points = rigid_points(observation, options_.scan);
  prepared.level_count = options_.strategy == SearchStrategy::Multires ? options_.levels : 1;
  prepared.levels = search_levels(observation, prepared.points ? &*prepared.points : nullptr,
                                  prepared.level_count, prepared.options.threads);
  check_resources(map_.geometry, options_, reach_,
                  search_size(prepared.lattice, prepared.levels.front(), options_.strategy,
                              prepared.level_count, false),
                  positive_only_);
  prepared.search.emplace(prepared.lattice, prepared.levels, pyramid_);
  if (hypotheses_in_one_pass(options_, hypotheses, observation)) {
    // The hypotheses after the winner lie outside its neighbourhood: poses within it need
    // not be kept.
    prepared.search->bnb.keep_share = options_.second_peak_floor;
    prepared.search->bnb.keep_outside =
        neighbourhood(LatticePose{}, options_.resolution, prepared.lattice, options_);
  }
}

Estimate CorrelationEstimator::conclude(PreparedSearch& prepared, const Observation& observation,
                                        const SearchWindow& window) const {
  WindowSearch& search = *prepared.search;
  const Lattice& lattice = prepared.lattice;
  const LatticePose& best = search.result.best;
  Estimate e;
  place_winner(e, search, map_.geometry, options_);
  e.score = best.score;
  e.agreement = observation.scan || observation.points
                    ? std::numeric_limits<double>::quiet_NaN()
                    : reading_agreement(map_, ring_of(observation), observation.ranges,
                                        observation.rejected, e.pose);
  const std::array<int, 3> sides =
      window_edge_sides(best, lattice, window, map_.geometry, options_.resolution);
  e.on_window_edge = sides != std::array<int, 3>{0, 0, 0};
  e.rises_past_window_edge = e.on_window_edge && rises_past_edge(search, sides);
  // The winning heading's local grid: the most any pose could score.
  const double mass =
      search.finest().make_local(lattice.theta(best.it), Eigen::Vector2d::Zero()).mass();
  e.normalized_score = mass > 0.0 ? e.score / mass : 0.0;
  const Peaks found = this_many_hypotheses(search, prepared.options, observation, prepared.start);
  const std::vector<LatticePose>& peaks = found.poses;
  e.second_score = peaks.size() > 1 ? peaks[1].score : found.floor.value_or(e.score);
  e.second_below_floor = peaks.size() == 1 && found.floor.has_value();
  for (const auto& p : peaks) {
    e.alternatives.push_back(
        {lattice_to_world(map_.geometry, lattice, options_.resolution, p.ix, p.iy, p.it), p.score});
  }
  if (options_.covariance_cells > 0) {
    // The verdict reads the spread at covariance_temperature; the answer reports its own.
    const std::vector<Eigen::Matrix3d> c = winner_covariances(
        search, options_.covariance_cells, map_.geometry.yaw,
        {options_.covariance_temperature, reported_temperature(observation, options_)});
    e.confidence_parts.spread_m = position_spread(c[0]);
    e.covariance = c[1];
    share_quantization(e.covariance, observation, lattice, options_);
    if (options_.covariance_spans_peaks) {
      e.covariance =
          spanning_peaks(e.covariance, e.alternatives, reported_temperature(observation, options_));
    }
  }
  judge(e, peaks.size() > 1 || e.second_below_floor, options_.verdict);
  fill_stats(e, search.result, prepared.level_count, prepared.start);
  return e;
}

std::vector<SearchLevel> CorrelationEstimator::search_levels(const Observation& observation,
                                                             const ScanPoints* points, int count,
                                                             int threads) const {
  std::vector<SearchLevel> levels;
  levels.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int l = 0; l < count; ++l) {
    levels.push_back(
        {&levels_[static_cast<std::size_t>(l)],
         [this, &observation, points, level_res = level_resolution(options_.resolution, l)](
             double theta, const Eigen::Vector2d& centre) {
           return local_grid(observation, points, theta, level_res, centre);
         },
         threads});
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
  const SearchLevel level =
      search_levels(observation, points ? &*points : nullptr, 1, options_.threads).front();
  check_resources(map_.geometry, options_, reach_,
                  search_size(lattice, level, SearchStrategy::Exhaustive, 1, true), positive_only_);
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
  return rasterize(ring_of(observation), observation.ranges, theta, resolution, options_.local,
                   centre, options_.sonar, observation.rejected);
}

}  // namespace gridloc
