// Tests of engine/src/localizer/hypothesis_set.cpp: seeding from a global estimate, merging
// and pruning, the set's answer; and that a global search's distinct poses are distinct
// across +-pi (the neighbourhoods wrap).
#include "gridloc/engine/localizer/hypothesis_set.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gridloc/engine/correlation/estimator.hpp"
#include "laser_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

Estimate global_with(const std::vector<Hypothesis>& peaks) {
  Estimate e;
  e.pose = peaks.front().pose;
  e.score = peaks.front().score;
  e.alternatives = peaks;
  e.verdict = Verdict::Localized;
  return e;
}

TEST(HypothesisSet, SeedsTheAlternativesWithinTheDropRatio) {
  const Estimate global = global_with({{{1, 1, 0}, 100}, {{5, 1, 0}, 90}, {{9, 1, 0}, 70}});
  HypothesisSetOptions options;
  options.drop_ratio = 0.8;
  const HypothesisSet set = seed_hypotheses(global, options);
  ASSERT_EQ(set.hypotheses.size(), 2u);
  EXPECT_EQ(set.hypotheses[1].pose.x, 5.0);
  EXPECT_EQ(set.elsewhere_score, 70.0);
  EXPECT_FALSE(set.crowded);
  options.max_hypotheses = 1;
  const HypothesisSet one = seed_hypotheses(global, options);
  ASSERT_EQ(one.hypotheses.size(), 1u);
  EXPECT_TRUE(one.crowded);  // a place it does not hold scores 90 % of the best
}

TEST(HypothesisSet, MergesThoseThatMetAndDropsThoseFarBelow) {
  std::vector<TrackedHypothesis> set = {{{1.0, 1.0, 0.0}, {}, 80, {}},
                                        {{1.1, 1.0, 0.05}, {}, 95, {}},  // meets the first
                                        {{4.0, 1.0, 0.0}, {}, 90, {}},
                                        {{4.0, 1.0, 3.0}, {}, 60, {}}};  // far below
  HypothesisSetOptions options;
  options.drop_ratio = 0.8;
  merge_and_prune(set, options);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set[0].score, 95.0);
  EXPECT_EQ(set[1].pose.x, 4.0);
}

TEST(HypothesisSet, TheAnswerIsAmbiguousWhileALookAlikeSurvives) {
  HypothesisSet set;
  Estimate best;
  best.verdict = Verdict::Localized;
  set.hypotheses = {{{1, 1, 0}, {}, 100, best}, {{5, 1, 0}, {}, 98, best}};
  Estimate e = set_estimate(set);
  EXPECT_EQ(e.verdict, Verdict::Ambiguous);
  ASSERT_EQ(e.alternatives.size(), 2u);
  set.hypotheses.pop_back();
  e = set_estimate(set);
  EXPECT_EQ(e.verdict, Verdict::Localized);
  test::expect_error([] { set_estimate({}); }, {"no hypothesis"});
  HypothesisSetOptions bad;
  bad.drop_ratio = 0.0;
  test::expect_error([&] { seed_hypotheses(e, bad); }, {"drop_ratio"});
  bad = {};
  bad.max_hypotheses = 0;
  test::expect_error([&] { seed_hypotheses(e, bad); }, {"max_hypotheses"});
}

TEST(HypothesisSet, AGlobalSearchsDistinctPosesAreDistinctAcrossPi) {
  const OccupancyMap map = test::door_corridor();
  CorrelationOptions options;
  options.resolution = 0.05;
  options.reach_m = 3.0;
  const CorrelationEstimator estimator(map, options);
  Observation observation;
  observation.scan = test::front_scan(map, {8.5, 2.5, 0.0}, 3.0);
  const Estimate e = estimator.estimate(observation, estimator.global_window(observation), 6);
  for (std::size_t a = 0; a < e.alternatives.size(); ++a) {
    for (std::size_t b = a + 1; b < e.alternatives.size(); ++b) {
      const Pose2& p = e.alternatives[a].pose;
      const Pose2& q = e.alternatives[b].pose;
      const bool distinct = std::hypot(p.x - q.x, p.y - q.y) > options.distinct_xy ||
                            std::abs(normalize_angle(p.theta - q.theta)) > options.distinct_theta;
      EXPECT_TRUE(distinct) << a << " and " << b << " at " << p.x << ", " << p.theta;
    }
  }
}

}  // namespace
}  // namespace gridloc
