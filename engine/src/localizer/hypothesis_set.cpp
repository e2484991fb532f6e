// Hypotheses that survive motion: seeding, merging and pruning, the set's answer.
#include "gridloc/engine/localizer/hypothesis_set.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const HypothesisSetOptions& options) {
  if (options.max_hypotheses < 1) {
    throw Error("hypothesis set: max_hypotheses must be at least 1, got " +
                std::to_string(options.max_hypotheses));
  }
  if (!(options.drop_ratio > 0.0 && options.drop_ratio <= 1.0)) {
    throw Error("hypothesis set: drop_ratio must lie in (0, 1], got " +
                std::to_string(options.drop_ratio));
  }
  if (!(options.merge_xy >= 0.0) || !std::isfinite(options.merge_xy) ||
      !(options.merge_theta >= 0.0) || !std::isfinite(options.merge_theta)) {
    throw Error("hypothesis set: merge_xy and merge_theta must be finite and >= 0");
  }
}

bool have_met(const Pose2& a, const Pose2& b, const HypothesisSetOptions& options) {
  return std::hypot(a.x - b.x, a.y - b.y) <= options.merge_xy &&
         std::abs(normalize_angle(a.theta - b.theta)) <= options.merge_theta;
}

HypothesisSet seed_hypotheses(const Estimate& global, const HypothesisSetOptions& options) {
  validate(options);
  HypothesisSet set;
  const double best = global.score;
  const auto limit = static_cast<std::size_t>(options.max_hypotheses);
  for (std::size_t k = 0; k < global.alternatives.size(); ++k) {
    const Hypothesis& peak = global.alternatives[k];
    if (k >= limit) {
      set.elsewhere_score = peak.score;
      set.crowded = peak.score >= options.drop_ratio * best && best > 0.0;
      break;
    }
    if (k > 0 && peak.score < options.drop_ratio * best) {
      set.elsewhere_score = peak.score;
      break;
    }
    set.hypotheses.push_back(
        {k == 0 ? global.pose : peak.pose, global.covariance, peak.score, global});
  }
  merge_and_prune(set.hypotheses, options);  // the refined winner may meet a lattice peak
  return set;
}

void merge_and_prune(std::vector<TrackedHypothesis>& hypotheses,
                     const HypothesisSetOptions& options) {
  std::stable_sort(
      hypotheses.begin(), hypotheses.end(),
      [](const TrackedHypothesis& a, const TrackedHypothesis& b) { return a.score > b.score; });
  std::vector<TrackedHypothesis> kept;
  for (TrackedHypothesis& h : hypotheses) {
    if (!kept.empty() && h.score < options.drop_ratio * kept.front().score) break;
    const bool met = std::any_of(kept.begin(), kept.end(), [&](const TrackedHypothesis& k) {
      return have_met(k.pose, h.pose, options);
    });
    if (!met) kept.push_back(std::move(h));
    if (kept.size() == static_cast<std::size_t>(options.max_hypotheses)) break;
  }
  hypotheses = std::move(kept);
}

Estimate set_estimate(const HypothesisSet& set) {
  if (set.hypotheses.empty()) throw Error("hypothesis set: no hypothesis to answer with");
  const TrackedHypothesis& best = set.hypotheses.front();
  Estimate e = best.estimate;
  e.alternatives.clear();
  for (const TrackedHypothesis& h : set.hypotheses) e.alternatives.push_back({h.pose, h.score});
  if (set.hypotheses.size() > 1) {
    e.ambiguous = true;
    e.verdict = Verdict::Ambiguous;
  }
  return e;
}

}  // namespace gridloc
