// A global search on a coarse copy of the map, refined at the map's own cell.
#include "gridloc/engine/correlation/coarse_to_fine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "confidence.hpp"
#include "gridloc/engine/correlation/scan_checks.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace {

/// Throws naming `field` and its value unless `ok` (option_checks.hpp's one form).
void require(bool ok, const char* field, double value, const char* rule) {
  require_option(ok, "coarse-to-fine search", field, value, rule);
}

const std::shared_ptr<const CorrelationEstimator>& checked(
    const std::shared_ptr<const CorrelationEstimator>& fine, const CoarseToFineOptions& options) {
  if (!fine) throw Error("coarse-to-fine search: no fine estimator");
  validate(options, fine->options().resolution);
  return fine;
}

/// The fine options at the coarse cell (on a likelihood field when options.field), reporting
/// `places` places and no covariance (the answer's comes from its fine window).
CorrelationOptions coarse_options(const CorrelationOptions& fine,
                                  const CoarseToFineOptions& options) {
  CorrelationOptions coarse = fine;
  coarse.resolution = options.resolution;
  // The places are found as the second peak is (above the floor, in the same search) even
  // when the answer's second peak is not asked for: they are what the answer is chosen from.
  coarse.hypotheses = options.places;
  coarse.second_peak = true;
  coarse.covariance_cells = 0;
  coarse.refine = false;  // each place is looked for again at the fine cell
  // The coarse copy searches the whole map: a bound pyramid as deep as it, whatever depth the
  // fine estimator was built to (its refinement windows need only a few levels). Capped as
  // the fine one was, a 250 m map's coarse search started from 850 000 blocks of 32 cells
  // and headings, best first in one heap: 1.6-2.3x slower (README, issue 35).
  coarse.max_bound_depth = 0;
  if (options.field) {
    coarse.global = GlobalModel::LikelihoodField;
    coarse.field.sigma_m = options.resolution;
    coarse.field.cutoff_m = 2.0 * options.resolution;
    coarse.field.free_value = -1.0;
  }
  return coarse;
}

bool distinct(const Pose2& a, const Pose2& b, const CorrelationOptions& options) {
  return std::hypot(a.x - b.x, a.y - b.y) > options.distinct_xy ||
         std::abs(normalize_angle(a.theta - b.theta)) > options.distinct_theta;
}

/// Whether a place apart from the best but within the verdict's ambiguity distances of it
/// scores `ridge_ratio` of the best (CoarseToFineOptions::ridge_ratio).
bool on_a_ridge(const Estimate& e, const VerdictOptions& verdict, double ridge_ratio) {
  return std::any_of(e.alternatives.begin() + 1, e.alternatives.end(), [&](const Hypothesis& h) {
    const double far = std::hypot(h.pose.x - e.lattice_pose.x, h.pose.y - e.lattice_pose.y);
    const double turn = std::abs(normalize_angle(h.pose.theta - e.lattice_pose.theta));
    return h.score >= ridge_ratio * e.score && far <= verdict.ambiguity_xy &&
           turn <= verdict.ambiguity_theta;
  });
}

/// The best refined place with the others as its hypotheses (distinct ones, best first, up to
/// options.hypotheses), its second score and verdict as the exact search would give them, but
/// for the ratios of `c2f` (CoarseToFineOptions::ambiguity_ratio, ridge_ratio). The window
/// edge flags are the coarse search's (`rough`), over the caller's window: a refinement
/// window's edges are not the caller's.
Estimate best_of(std::vector<Estimate> refined, const Estimate& rough,
                 const CorrelationOptions& options, const CoarseToFineOptions& c2f) {
  std::stable_sort(refined.begin(), refined.end(),
                   [](const Estimate& a, const Estimate& b) { return a.score > b.score; });
  Estimate e = refined.front();
  e.on_window_edge = rough.on_window_edge;
  e.rises_past_window_edge = rough.rises_past_window_edge;
  e.alternatives = {{e.lattice_pose, e.score}};
  const auto wanted = static_cast<std::size_t>(std::max(1, options.hypotheses));
  for (std::size_t k = 1; k < refined.size() && e.alternatives.size() < wanted; ++k) {
    const Pose2& pose = refined[k].lattice_pose;
    const bool apart =
        std::all_of(e.alternatives.begin(), e.alternatives.end(),
                    [&](const Hypothesis& h) { return distinct(h.pose, pose, options); });
    if (apart) e.alternatives.push_back({pose, refined[k].score});
  }
  const bool floor = options.second_peak_floor > 0.0 && e.score > 0.0;
  const bool second = e.alternatives.size() > 1;
  e.second_score = second  ? e.alternatives[1].score
                   : floor ? options.second_peak_floor * e.score
                           : e.score;
  e.second_below_floor = !second && floor;
  VerdictOptions verdict = options.verdict;
  verdict.ambiguity_ratio = c2f.ambiguity_ratio;
  correlation_detail::judge(e, second || e.second_below_floor, verdict);
  if (e.verdict == Verdict::Localized && e.score > 0.0 && on_a_ridge(e, verdict, c2f.ridge_ratio)) {
    e.verdict = Verdict::NotLocalized;
  }
  return e;
}

/// The through-walls check of `options` (its window is the caller's: no edge rule).
ScanChecks scan_checks(const CoarseToFineOptions& options) {
  ScanChecks checks;
  checks.through_wall_ratio = options.through_wall_ratio;
  checks.through_wall_margin_m = options.through_wall_margin_m;
  checks.edge_not_localized = false;
  checks.close_second_ratio = 0.0;  // whole-map answers: issue 35's rules
  return checks;
}

/// `pose` moved onto the nearest cell centre of `map` when it lies past the map's edge (the
/// last cell of the coarse copy overhangs the map when its side is no whole number of them).
Pose2 inside(const GridGeometry& map, const Pose2& pose) {
  Pose2 local = map.to_grid_frame(pose);
  const double res = map.resolution;
  local.x = std::clamp(local.x, 0.5 * res, (map.width - 0.5) * res);
  local.y = std::clamp(local.y, 0.5 * res, (map.height - 0.5) * res);
  return map.to_world_frame(local);
}

void add_counts(SearchStats& total, const SearchStats& one) {
  total.poses_scored += one.poses_scored;
  total.cells_scored += one.cells_scored;
}

}  // namespace

void validate(const CoarseToFineOptions& options, double fine_resolution) {
  require(std::isfinite(options.resolution) && options.resolution > fine_resolution &&
              options.resolution <= kMaxCoarseCell,
          "resolution", options.resolution, "must be coarser than the fine cell and at most 0.5 m");
  require(options.places >= 1 && options.places <= kMaxPlaces, "places", options.places,
          "must lie in [1, 100]");
  require(options.ambiguity_ratio > 0.0 && options.ambiguity_ratio <= 1.0, "ambiguity_ratio",
          options.ambiguity_ratio, "must lie in (0, 1]");
  require(options.ridge_ratio > 0.0 && options.ridge_ratio <= 1.0, "ridge_ratio",
          options.ridge_ratio, "must lie in (0, 1]");
  require(std::isfinite(options.through_wall_ratio) && options.through_wall_ratio >= 0.0,
          "through_wall_ratio", options.through_wall_ratio, "must be finite and >= 0");
  require(std::isfinite(options.through_wall_margin_m) && options.through_wall_margin_m >= 0.0,
          "through_wall_margin_m", options.through_wall_margin_m, "must be finite and >= 0");
  require(std::isfinite(options.reported_floor_m) && options.reported_floor_m >= 0.0,
          "reported_floor_m", options.reported_floor_m, "must be finite and >= 0");
  require(std::isfinite(options.reported_floor_rad) && options.reported_floor_rad >= 0.0,
          "reported_floor_rad", options.reported_floor_rad, "must be finite and >= 0");
  require(std::isfinite(options.half_xy_cells) && options.half_xy_cells > 0.0, "half_xy_cells",
          options.half_xy_cells, "must be finite and > 0");
  require(std::isfinite(options.half_theta_steps) && options.half_theta_steps > 0.0,
          "half_theta_steps", options.half_theta_steps, "must be finite and > 0");
}

int refinement_bound_depth(const CoarseToFineOptions& options, double fine_resolution) {
  validate(options, fine_resolution);
  SearchWindow window;
  window.step_xy = fine_resolution;
  window.half_xy = options.half_xy_cells * options.resolution;
  return window_bound_depth(window);
}

CoarseToFineEstimator::CoarseToFineEstimator(std::shared_ptr<const CorrelationEstimator> fine,
                                             CoarseToFineOptions options)
    : fine_(checked(fine, options)),
      options_(options),
      coarse_(fine_->map(), fine_->ring(), coarse_options(fine_->options(), options)) {}

Estimate CoarseToFineEstimator::estimate(const Observation& observation,
                                         const SearchWindow& window) const {
  const auto start = std::chrono::steady_clock::now();
  const SearchWindow coarse = coarse_window(observation, window);
  const Estimate rough = coarse_.estimate(observation, coarse);
  std::vector<Estimate> refined;
  for (const Hypothesis& place : rough.alternatives) {
    refined.push_back(refine_place(observation, place.pose, coarse.step_theta, window.step_theta));
  }
  SearchStats stats = rough.stats;
  for (const Estimate& r : refined) add_counts(stats, r.stats);
  Estimate e = best_of(std::move(refined), rough, fine_->options(), options_);
  if (observation.scan)
    check_scan_answer(e, fine_->map(), *observation.scan, scan_checks(options_));
  add_reported_floor(e, options_.reported_floor_m, options_.reported_floor_rad);
  e.stats = stats;
  e.stats.levels = 2;
  e.stats.proven_optimal = false;  // the coarse copy chose the places looked at closely
  e.stats.upper_bound = std::numeric_limits<double>::quiet_NaN();
  e.stats.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return e;
}

SearchWindow CoarseToFineEstimator::coarse_window(const Observation& observation,
                                                  const SearchWindow& window) const {
  const SearchWindow whole = coarse_.global_window(observation);
  SearchWindow coarse = window;
  coarse.step_xy = options_.resolution;
  // Every fine cell inside a coarse one, and at most the whole map.
  coarse.half_xy = std::min(window.half_xy + options_.resolution, whole.half_xy);
  coarse.step_theta = std::max(window.step_theta, whole.step_theta);
  return coarse;
}

Estimate CoarseToFineEstimator::refine_place(const Observation& observation, const Pose2& place,
                                             double coarse_step_theta,
                                             double fine_step_theta) const {
  SearchWindow window;
  window.center = inside(fine_->map().geometry, place);
  window.step_xy = fine_->options().resolution;
  window.step_theta = fine_step_theta;
  // At most the whole map (a map narrower than a window).
  window.half_xy = std::min(options_.half_xy_cells * options_.resolution,
                            fine_->global_window(observation).half_xy);
  window.half_theta = std::min(std::numbers::pi, options_.half_theta_steps * coarse_step_theta);
  return fine_->estimate(observation, window, 1);
}

}  // namespace gridloc
