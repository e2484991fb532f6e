// The tracked places' weights: evidence added per observation, newcomers' entry weight,
// normalization, merging and pruning by weight.
#include "gridloc/engine/localizer/hypothesis_weights.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace {

void require(bool ok, const char* field, double value, const char* rule) {
  require_option(ok, "hypothesis weights", field, value, rule);
}

double max_log_weight(const std::vector<TrackedHypothesis>& hypotheses) {
  double best = -std::numeric_limits<double>::infinity();
  for (const TrackedHypothesis& h : hypotheses) best = std::max(best, h.log_weight);
  return best;
}

/// log(e^a + e^b), stable.
double log_add(double a, double b) {
  const double high = std::max(a, b), low = std::min(a, b);
  return high + std::log1p(std::exp(low - high));
}

}  // namespace

void validate(const HypothesisWeightOptions& options) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(positive(options.evidence_per_scan), "evidence_per_scan", options.evidence_per_scan,
          "must be finite and > 0");
  require(positive(options.entry_weight) && options.entry_weight <= 1.0, "entry_weight",
          options.entry_weight, "must lie in (0, 1]");
  require(positive(options.unsure_entry_weight) && options.unsure_entry_weight <= 1.0,
          "unsure_entry_weight", options.unsure_entry_weight, "must lie in (0, 1]");
  require(options.localized_weight > 0.5 && options.localized_weight <= 1.0, "localized_weight",
          options.localized_weight, "must lie in (0.5, 1]");
  require(options.min_weight >= 0.0 && options.min_weight < 0.5, "min_weight", options.min_weight,
          "must lie in [0, 0.5)");
  require(std::isfinite(options.newcomer_settle_m) && options.newcomer_settle_m >= 0.0,
          "newcomer_settle_m", options.newcomer_settle_m, "must be finite and >= 0");
  require(std::isfinite(options.update_min_m) && options.update_min_m >= 0.0, "update_min_m",
          options.update_min_m, "must be finite and >= 0");
  require(std::isfinite(options.update_min_rad) && options.update_min_rad >= 0.0, "update_min_rad",
          options.update_min_rad, "must be finite and >= 0");
}

void add_evidence(std::vector<TrackedHypothesis>& hypotheses,
                  const HypothesisWeightOptions& options) {
  for (TrackedHypothesis& h : hypotheses) {
    h.log_weight += options.evidence_per_scan * h.estimate.normalized_score;
  }
  normalize_weights(hypotheses);
}

double entry_log_weight(const std::vector<TrackedHypothesis>& tracked, double normalized_score,
                        const HypothesisWeightOptions& options) {
  if (tracked.empty()) return options.evidence_per_scan * normalized_score;
  const auto heaviest =
      std::max_element(tracked.begin(), tracked.end(),
                       [](const auto& a, const auto& b) { return a.log_weight < b.log_weight; });
  const bool track = heaviest->confirmed && heaviest->weight >= options.localized_weight;
  return heaviest->log_weight +
         std::log(track ? options.entry_weight : options.unsure_entry_weight) +
         options.evidence_per_scan * (normalized_score - heaviest->estimate.normalized_score);
}

void normalize_weights(std::vector<TrackedHypothesis>& hypotheses) {
  if (hypotheses.empty()) return;
  const double top = max_log_weight(hypotheses);
  double total = 0.0;
  for (const TrackedHypothesis& h : hypotheses) total += std::exp(h.log_weight - top);
  for (TrackedHypothesis& h : hypotheses) {
    h.log_weight -= top;  // keeps the numbers small over a long run
    h.weight = std::exp(h.log_weight) / total;
  }
}

void merge_and_prune_weighted(std::vector<TrackedHypothesis>& hypotheses,
                              const HypothesisSetOptions& set_options,
                              const HypothesisWeightOptions& options) {
  const auto heavier = [](const TrackedHypothesis& a, const TrackedHypothesis& b) {
    return a.log_weight > b.log_weight;
  };
  std::stable_sort(hypotheses.begin(), hypotheses.end(), heavier);
  std::vector<TrackedHypothesis> kept;
  for (TrackedHypothesis& h : hypotheses) {
    const auto met = std::find_if(kept.begin(), kept.end(), [&](const TrackedHypothesis& k) {
      return have_met(k.pose, h.pose, set_options);
    });
    if (met == kept.end()) {
      kept.push_back(std::move(h));
    } else {
      met->log_weight = log_add(met->log_weight, h.log_weight);
    }
  }
  std::stable_sort(kept.begin(), kept.end(), heavier);  // merged weights may reorder them
  normalize_weights(kept);
  std::erase_if(kept, [&](const TrackedHypothesis& h) { return h.weight < options.min_weight; });
  if (kept.size() > static_cast<std::size_t>(set_options.max_hypotheses)) {
    kept.resize(static_cast<std::size_t>(set_options.max_hypotheses));
  }
  normalize_weights(kept);
  hypotheses = std::move(kept);
}

Estimate weighted_estimate(const std::vector<TrackedHypothesis>& hypotheses,
                           const HypothesisWeightOptions& options) {
  if (hypotheses.empty()) throw Error("hypothesis weights: no hypothesis to answer with");
  const TrackedHypothesis& best = hypotheses.front();
  Estimate e = best.estimate;
  e.pose = best.pose;
  e.covariance = best.covariance;
  e.alternatives.clear();
  for (const TrackedHypothesis& h : hypotheses)
    e.alternatives.push_back({h.pose, h.score, h.weight});
  if (best.newcomer && best.driven_m < options.newcomer_settle_m) {
    e.verdict = Verdict::NotLocalized;
  } else if (e.verdict != Verdict::NotLocalized && best.weight < options.localized_weight) {
    e.ambiguous = true;
    e.verdict = Verdict::Ambiguous;
  }
  return e;
}

}  // namespace gridloc
