// Tests of engine/src/localizer/hypothesis_weights.cpp: evidence adds up, a newcomer enters
// with a small share unless it explains the scan much better, merging sums the weights,
// pruning drops the light places, and the answer's verdict follows the shares.
#include "gridloc/engine/localizer/hypothesis_weights.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace gridloc {
namespace {

TrackedHypothesis place(double x, double normalized_score, Verdict verdict = Verdict::Localized) {
  TrackedHypothesis h;
  h.pose = {x, 1.0, 0.0};
  h.estimate.normalized_score = normalized_score;
  h.estimate.verdict = verdict;
  h.score = normalized_score;
  return h;
}

TEST(HypothesisWeights, EvidenceAddsUpOverObservations) {
  HypothesisWeightOptions options;
  options.evidence_per_scan = 10.0;
  std::vector<TrackedHypothesis> set = {place(1, 0.8), place(5, 0.7)};
  add_evidence(set, options);
  EXPECT_NEAR(set[0].weight / set[1].weight, std::exp(1.0), 1e-9);
  add_evidence(set, options);  // the same again: twice the evidence
  EXPECT_NEAR(set[0].weight / set[1].weight, std::exp(2.0), 1e-9);
  EXPECT_NEAR(set[0].weight + set[1].weight, 1.0, 1e-12);
}

TEST(HypothesisWeights, ANewcomerEntersSmallUnlessItExplainsMuchBetter) {
  HypothesisWeightOptions options;
  options.evidence_per_scan = 20.0;
  options.entry_weight = 1e-3;
  std::vector<TrackedHypothesis> set = {place(1, 0.8)};
  set[0].confirmed = true;  // a track: its window placed it
  add_evidence(set, options);
  // As good as the track: a thousandth of its weight.
  TrackedHypothesis same = place(9, 0.8);
  same.log_weight = entry_log_weight(set, 0.8, options);
  std::vector<TrackedHypothesis> with_same = set;
  with_same.push_back(same);
  normalize_weights(with_same);
  EXPECT_NEAR(with_same[1].weight / with_same[0].weight, 1e-3, 1e-12);
  // Explaining the scan 0.5 better (the track is lost): e^10 / 1000 = 22 times the track.
  TrackedHypothesis better = place(9, 1.3);
  better.log_weight = entry_log_weight(set, 1.3, options);
  set.push_back(better);
  normalize_weights(set);
  EXPECT_NEAR(set[1].weight / set[0].weight, std::exp(10.0) * 1e-3, 1e-6);
  // A prior nothing confirmed was never sure: newcomers enter with a tenth of its weight.
  std::vector<TrackedHypothesis> prior = {place(1, 0.8)};
  normalize_weights(prior);
  EXPECT_NEAR(entry_log_weight(prior, 0.9, options), prior[0].log_weight + std::log(0.1) + 2.0,
              1e-12);
  // With nothing tracked, newcomers compete by score alone.
  EXPECT_EQ(entry_log_weight({}, 0.5, options), 10.0);
}

TEST(HypothesisWeights, MergingSumsAndPruningDropsTheLight) {
  HypothesisSetOptions set_options;
  set_options.max_hypotheses = 2;
  HypothesisWeightOptions options;
  options.min_weight = 0.01;
  std::vector<TrackedHypothesis> set = {place(1.0, 0), place(1.1, 0), place(5, 0), place(9, 0)};
  set[0].log_weight = std::log(0.3);
  set[1].log_weight = std::log(0.3);  // meets the first: one place with 0.6
  set[2].log_weight = std::log(0.395);
  set[3].log_weight = std::log(0.005);  // below min_weight
  merge_and_prune_weighted(set, set_options, options);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set[0].pose.x, 1.0);
  EXPECT_NEAR(set[0].weight, 0.6 / 0.995, 1e-9);
  EXPECT_EQ(set[1].pose.x, 5.0);
}

TEST(HypothesisWeights, TheVerdictFollowsTheShares) {
  HypothesisWeightOptions options;
  std::vector<TrackedHypothesis> set = {place(1, 0.8), place(5, 0.8)};
  set[0].weight = 0.995;
  set[1].weight = 0.005;
  Estimate e = weighted_estimate(set, options);
  EXPECT_EQ(e.verdict, Verdict::Localized);
  ASSERT_EQ(e.alternatives.size(), 2u);
  EXPECT_EQ(e.alternatives[1].weight, 0.005);
  set[0].weight = 0.9;
  set[1].weight = 0.1;
  EXPECT_EQ(weighted_estimate(set, options).verdict, Verdict::Ambiguous);
  set[0].estimate.verdict = Verdict::NotLocalized;  // the heaviest place explains nothing
  EXPECT_EQ(weighted_estimate(set, options).verdict, Verdict::NotLocalized);
  test::expect_error([&] { weighted_estimate({}, options); }, {"no hypothesis"});
  HypothesisWeightOptions bad;
  bad.entry_weight = 0.0;
  test::expect_error([&] { validate(bad); }, {"entry_weight"});
  bad = {};
  bad.localized_weight = 0.4;
  test::expect_error([&] { validate(bad); }, {"localized_weight"});
}

}  // namespace
}  // namespace gridloc
