// The Localizer's re-searches: when one starts, its steps an update, and how its places join
// the tracked ones once it is done (caught up through the observations taken meanwhile).
#include <algorithm>
#include <cmath>

#include "gridloc/engine/localizer/localizer.hpp"

namespace gridloc {

std::optional<Estimate> Localizer::advance_search(LocalizerState& next,
                                                  std::vector<TrackedHypothesis>& tracked,
                                                  const Pose2& taken_at,
                                                  const Observation& observation) const {
  const bool ambiguous = next.estimate && next.estimate->verdict == Verdict::Ambiguous;
  const bool lost = tracked.empty() || tracked.front().misses >= options_.misses_before_global;
  const bool settled = next.estimate && next.estimate->verdict == Verdict::Localized &&
                       tracked.size() == 1 && tracked.front().misses == 0;
  if (next.search && settled && options_.research.drop_once_localized) next.search.reset();
  if (!next.search && (lost || (ambiguous && next.since_global_m >= options_.reseed_after_m))) {
    const CorrelationEstimator& searcher = search_estimator(!next.estimate);
    const SearchWindow global = searcher.global_window(observation);
    const int slices = next.estimate
                           ? slice_count(searcher.lattice(observation, global), options_.research)
                           : 1;  // the first observation's search answers at once
    const int seeds = options_.hypothesis_set.max_hypotheses + 1;
    const int whole = coarse_ ? 2 * seeds : seeds;  // the peaks of a search run whole
    const double cells = options_.research.cells_per_update;
    if (slices > 1 && cells > 0.0) {  // one search, a budget of it per update
      next.search.emplace(observation, taken_at,
                          PendingEstimate(searcher, observation, global, whole), cells);
    } else {
      const int peaks = slices == 1 ? whole : options_.research.peaks_per_slice;
      next.search.emplace(observation, taken_at, global, slices, peaks);
    }
    next.since_global_m = 0.0;
  }
  if (!next.search) return std::nullopt;
  const bool first = !next.estimate;
  const CorrelationEstimator& searcher = search_estimator(first);
  next.search->run(searcher, first ? next.search->slices() : options_.research.slices_per_update);
  next.status.search_slices_done = next.search->slices_done();
  next.status.search_slices = next.search->slices();
  next.status.search_progress = next.search->progress();
  if (!next.search->done()) {
    next.search->record({taken_at, next.since_global_m, observation},
                        options_.research.catch_up_steps);
    return std::nullopt;
  }
  Estimate global = next.search->result(searcher.options());
  const bool coarse = &searcher != &estimator_;
  if (coarse) {  // coarse places: their windows span a few coarse cells; the fine windows and
                 // the weights, not the coarse verdict, decide
    const double cell = searcher.options().resolution;
    const double step = searcher.global_window(next.search->observation()).step_theta;
    global.covariance = Eigen::Vector3d(cell * cell, cell * cell, 4.0 * step * step).asDiagonal();
  }
  if (coarse || global.verdict != Verdict::NotLocalized) {
    join(global, *next.search, tracked, {taken_at, next.since_global_m, observation}, !first);
  }
  next.search.reset();
  next.status.search_finished = true;
  for (TrackedHypothesis& h : tracked) h.misses = 0;  // a new search: count afresh
  return global;
}

void Localizer::join(const Estimate& global, const SlicedSearch& search,
                     std::vector<TrackedHypothesis>& tracked,
                     const SlicedSearch::PastObservation& now, bool newcomers) const {
  const std::vector<TrackedHypothesis> before = tracked;  // the entry weights refer to these
  // After a confirmed track was lost, its successor must first be carried a while; a prior
  // no window confirmed was never a track.
  const bool lost_a_track = std::any_of(before.begin(), before.end(),
                                        [](const TrackedHypothesis& h) { return h.confirmed; });
  const auto meets = [&](const TrackedHypothesis& seed) {
    return std::any_of(before.begin(), before.end(), [&](const TrackedHypothesis& h) {
      return have_met(seed.pose, h.pose, options_.hypothesis_set);
    });
  };
  HypothesisSetOptions seeding = options_.hypothesis_set;
  if (!newcomers && laser_) seeding.drop_ratio = options_.first_drop_ratio;  // a first scan
  for (TrackedHypothesis seed : seed_hypotheses(global, seeding).hypotheses) {
    std::optional<TrackedHypothesis> followed = catch_up(std::move(seed), search, now);
    if (!followed || meets(*followed)) continue;
    followed->log_weight =
        entry_log_weight(before, followed->estimate.normalized_score, options_.weights);
    followed->newcomer = newcomers && lost_a_track;
    followed->driven_m = 0.0;
    tracked.push_back(std::move(*followed));
  }
}

std::optional<TrackedHypothesis> Localizer::catch_up(
    TrackedHypothesis seed, const SlicedSearch& search,
    const SlicedSearch::PastObservation& now) const {
  const std::vector<SlicedSearch::PastObservation>& path = search.path();
  const std::size_t steps =
      std::min(path.size(), static_cast<std::size_t>(options_.research.catch_up_steps));
  Pose2 from = search.odometry();
  double from_m = 0.0;
  for (std::size_t k = 1; k <= steps + 1; ++k) {
    // Evenly spread along the path taken meanwhile, then the latest observation.
    const SlicedSearch::PastObservation& past =
        k <= steps ? path[k * path.size() / steps - 1] : now;
    const Pose2 moved = relative_pose(from, past.odometry);
    const double driven = steps > 0 ? past.driven_m - from_m : std::hypot(moved.x, moved.y);
    std::optional<TrackedHypothesis> followed =
        follow_one(std::move(seed), moved, driven, past.observation, nullptr);
    if (!followed) return std::nullopt;
    seed = std::move(*followed);
    from = past.odometry;
    from_m = past.driven_m;
  }
  return seed;
}

}  // namespace gridloc
