#pragma once
/// How much the evidence favours each tracked place (issue 34): every hypothesis carries the
/// sum of its observations' log-likelihoods since it entered (evidence_per_scan times the
/// window's normalized score), and a place a re-search proposes enters with a small prior
/// share (entry_weight) times what the current observation says of it against the track.
/// The shares, not one observation's scores, decide the verdict: `localized` only while one
/// place holds nearly all of it.
#include <vector>

#include "gridloc/engine/localizer/hypothesis_set.hpp"

namespace gridloc {

struct HypothesisWeightOptions {
  /// Log-likelihood per unit of normalized score of one observation: two places whose
  /// windows score 0.05 apart on one scan differ by a factor e^(0.05 * this).
  double evidence_per_scan = 20.0;
  /// The prior share of a place a re-search proposes against the places tracked: the chance
  /// that the track is wrong. It enters with this times e^(evidence * (its score - the best
  /// tracked place's score)), so it must explain the scan much better to matter at once.
  double entry_weight = 1e-3;
  /// The same against a set that is no confident track (look-alikes, or a prior no window
  /// confirmed): the newcomer's past evidence is unknown, but it did not make the set.
  double unsure_entry_weight = 0.1;
  double localized_weight = 0.99;  ///< `localized` needs one place to hold this share
  /// A re-search's place is not `localized` before it has been carried this far (m): after a
  /// loss the weights must have seen the place from more than one spot.
  double newcomer_settle_m = 2.0;
  double min_weight = 1e-4;  ///< places whose share falls below this are dropped
  /// The evidence is added only after the robot moved this far or turned this much since
  /// the last time (a standstill repeats the same view: no new information).
  double update_min_m = 0.05;
  double update_min_rad = 0.0349065850399;  ///< 2 deg
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const HypothesisWeightOptions& options);

/// Adds each hypothesis's latest observation (its `estimate.normalized_score`) to its
/// log weight, then normalize_weights.
void add_evidence(std::vector<TrackedHypothesis>& hypotheses,
                  const HypothesisWeightOptions& options);

/// The log weight a newcomer scoring `normalized_score` on the latest observation enters with
/// among `tracked` (their log weights and latest scores, heaviest first): against the
/// heaviest place, the evidence of its score over that place's, times entry_weight when that
/// place is a track (confirmed, holding localized_weight), unsure_entry_weight otherwise. With
/// nothing tracked: evidence_per_scan * normalized_score (newcomers of one search compete by score
/// alone).
double entry_log_weight(const std::vector<TrackedHypothesis>& tracked, double normalized_score,
                        const HypothesisWeightOptions& options);

/// Sets each `weight` to its share of the set (from the log weights; sums to 1).
void normalize_weights(std::vector<TrackedHypothesis>& hypotheses);

/// Merges hypotheses that have met (the heavier one stays and takes the other's weight),
/// drops those whose share is below min_weight, keeps the max_hypotheses heaviest, sorted
/// heaviest first, and normalizes the weights.
void merge_and_prune_weighted(std::vector<TrackedHypothesis>& hypotheses,
                              const HypothesisSetOptions& set_options,
                              const HypothesisWeightOptions& options);

/// The answer of a weighted set (heaviest first, not empty): the heaviest place's pose,
/// covariance and window estimate, every place as an alternative with its score and weight;
/// `not localized` when its window explained nothing or it is a re-search's place carried
/// less than newcomer_settle_m, `ambiguous` while it holds less than localized_weight, else
/// its window's own verdict.
Estimate weighted_estimate(const std::vector<TrackedHypothesis>& hypotheses,
                           const HypothesisWeightOptions& options);

}  // namespace gridloc
