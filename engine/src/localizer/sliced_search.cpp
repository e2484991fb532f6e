// A global search cut into heading slices, run a few slices per tracker update.
#include "gridloc/engine/localizer/sliced_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const SlicedSearchOptions& options) {
  if (!(options.poses_per_slice >= 0.0) || !std::isfinite(options.poses_per_slice)) {
    throw Error("sliced search: poses_per_slice must be finite and >= 0, got " +
                std::to_string(options.poses_per_slice));
  }
  if (options.slices_per_update < 1) {
    throw Error("sliced search: slices_per_update must be at least 1, got " +
                std::to_string(options.slices_per_update));
  }
  if (!(options.cells_per_update >= 0.0) || !std::isfinite(options.cells_per_update)) {
    throw Error("sliced search: cells_per_update must be finite and >= 0, got " +
                std::to_string(options.cells_per_update));
  }
  if (options.catch_up_steps < 0 || options.catch_up_steps > 1000) {
    throw Error("sliced search: catch_up_steps must lie in [0, 1000], got " +
                std::to_string(options.catch_up_steps));
  }
  if (!(options.resolution >= 0.0) || !std::isfinite(options.resolution)) {
    throw Error("sliced search: resolution must be finite and >= 0, got " +
                std::to_string(options.resolution));
  }
  if (options.peaks_per_slice < 1 || options.peaks_per_slice > 64) {
    throw Error("sliced search: peaks_per_slice must lie in [1, 64], got " +
                std::to_string(options.peaks_per_slice));
  }
}

int slice_count(const Lattice& lattice, const SlicedSearchOptions& options) {
  if (options.poses_per_slice <= 0.0) return 1;
  const double poses = double(lattice.x1 - lattice.x0 + 1) * double(lattice.y1 - lattice.y0 + 1) *
                       double(lattice.headings);
  const double slices = std::ceil(poses / options.poses_per_slice);
  return static_cast<int>(std::clamp(slices, 1.0, double(std::max(1, lattice.headings))));
}

SlicedSearch::SlicedSearch(Observation observation, const Pose2& odometry,
                           const SearchWindow& global, int slices, int peaks_per_slice)
    : observation_(std::move(observation)),
      odometry_(odometry),
      global_(global),
      slices_(std::max(1, slices)),
      peaks_per_slice_(std::max(1, peaks_per_slice)) {}

SlicedSearch::SlicedSearch(Observation observation, const Pose2& odometry, PendingEstimate pending,
                           double cells_per_update)
    : observation_(std::move(observation)),
      odometry_(odometry),
      pending_(std::move(pending)),
      cells_per_update_(cells_per_update) {}

double SlicedSearch::progress() const {
  if (pending_) return 1.0 - pending_->open_share();
  return double(next_) / double(slices_);
}

void SlicedSearch::record(PastObservation past, int keep) {
  if (keep <= 0) return;
  path_.push_back(std::move(past));
  if (path_.size() <= 2 * static_cast<std::size_t>(keep)) return;
  std::vector<PastObservation> thinned;
  for (std::size_t k = path_.size() % 2 == 0 ? 1 : 0; k < path_.size(); k += 2) {
    thinned.push_back(std::move(path_[k]));  // every other one, ending with the latest
  }
  path_ = std::move(thinned);
}

SearchWindow SlicedSearch::slice_window(int k) const {
  const double width = 2.0 * std::numbers::pi / slices_;
  SearchWindow window = global_;
  if (slices_ == 1) return window;
  // Half a step less than half the slice: neighbouring slices share no heading.
  window.half_theta = std::max(0.0, 0.5 * width - 0.5 * global_.step_theta);
  window.center.theta = normalize_angle(-std::numbers::pi + (k + 0.5) * width);
  return window;
}

void SlicedSearch::run(const CorrelationEstimator& estimator, int count) {
  if (pending_) {
    if (pending_->done()) return;
    const double cells = std::max(1.0, cells_per_update_ * std::max(1, count));
    pending_->advance(static_cast<long long>(std::min(cells, 9e18)));
    ++next_;
    if (pending_->done()) slices_ = next_;
    return;
  }
  for (int k = 0; k < count && !done(); ++k, ++next_) {
    found_.push_back(estimator.estimate(observation_, slice_window(next_), peaks_per_slice_));
  }
}

namespace {

bool distinct(const Pose2& a, const Pose2& b, const CorrelationOptions& options) {
  return std::hypot(a.x - b.x, a.y - b.y) > options.distinct_xy ||
         std::abs(normalize_angle(a.theta - b.theta)) > options.distinct_theta;
}

}  // namespace

Estimate SlicedSearch::result(const CorrelationOptions& options) const {
  if (pending_) return pending_->result();
  if (found_.empty()) throw Error("sliced search: no slice has run");
  const auto best = std::max_element(
      found_.begin(), found_.end(), [](const auto& a, const auto& b) { return a.score < b.score; });
  std::vector<Hypothesis> peaks;
  for (const Estimate& slice : found_) {
    peaks.insert(peaks.end(), slice.alternatives.begin(), slice.alternatives.end());
  }
  std::stable_sort(peaks.begin(), peaks.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.score > b.score; });
  Estimate merged = *best;
  merged.alternatives.clear();
  for (const Hypothesis& peak : peaks) {
    const bool kept =
        std::all_of(merged.alternatives.begin(), merged.alternatives.end(),
                    [&](const Hypothesis& h) { return distinct(h.pose, peak.pose, options); });
    if (kept) merged.alternatives.push_back(peak);
  }
  if (merged.alternatives.size() > 1) {
    merged.second_score = merged.alternatives[1].score;
    if (merged.second_score >= options.verdict.ambiguity_ratio * merged.score &&
        merged.verdict == Verdict::Localized) {
      merged.ambiguous = true;
      merged.verdict = Verdict::Ambiguous;
    }
  }
  return merged;
}

}  // namespace gridloc
