#include "gridloc/engine/disambiguation/minimum_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "disambiguation/comb_rooms.hpp"
#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"
#include "gridloc/engine/disambiguation/polygon_space.hpp"
#include "gridloc/engine/disambiguation/travel_bound.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

const Pose2 kStart{3.5, 0.5, 0.0};  // the middle room of the comb

MinimumDistancePlan plan_for(SamplingAlgorithm algorithm, DistanceStrategy strategy, double range,
                             std::uint64_t seed = 1, int threads = 1) {
  const Area map = test::comb_rooms();
  const std::vector<Pose2> hypotheses = start_hypotheses(map, kStart, {range, false, 1e-6});
  MinimumDistanceOptions options;
  options.algorithm = algorithm;
  options.strategy = strategy;
  options.points = 40;
  options.seed = seed;
  options.threads = threads;
  const PolygonPlanningSpace space(map, {range, 1e-6, 16});
  return localize_with_minimum_travel(space, hypotheses,
                                      perfect_sensing(map, kStart, hypotheses, range), options);
}

TEST(MinimumDistance, EveryAlgorithmAndStrategyResolvesToTheTruth) {
  for (const SamplingAlgorithm algorithm : {SamplingAlgorithm::Col, SamplingAlgorithm::Ual}) {
    for (const DistanceStrategy strategy : {DistanceStrategy::Weighted, DistanceStrategy::Hybrid}) {
      for (const double range : {kUnlimitedRange, 1.5}) {
        const MinimumDistancePlan plan = plan_for(algorithm, strategy, range);
        ASSERT_TRUE(plan.resolved) << plan.ended << " range " << range;
        EXPECT_EQ(plan.remaining, std::vector<int>{1});  // the middle room
        EXPECT_GE(plan.stops.size(), 1u);
        double length = 0.0;
        std::vector<int> eliminated;
        for (const LocalizationStop& stop : plan.stops) {
          length += stop.route_length;
          EXPECT_GT(stop.info, 0.0);
          EXPECT_GE(stop.route.size(), 2u);
          eliminated.insert(eliminated.end(), stop.eliminated.begin(), stop.eliminated.end());
        }
        EXPECT_NEAR(plan.path_length, length, 1e-9);
        std::sort(eliminated.begin(), eliminated.end());
        EXPECT_EQ(eliminated, (std::vector<int>{0, 2}));
      }
    }
  }
}

TEST(MinimumDistance, NoPathBeatsTheLowerBound) {
  const Area map = test::comb_rooms();
  for (const double range : {kUnlimitedRange, 1.5}) {
    const std::vector<Pose2> hypotheses = start_hypotheses(map, kStart, {range, false, 1e-6});
    const TravelBound bound =
        travel_lower_bound(PolygonPlanningSpace(map, {range, 1e-6, 16}), hypotheses, 1, 0.05);
    ASSERT_TRUE(std::isfinite(bound.distance));
    ASSERT_TRUE(std::isfinite(bound.pairwise));
    EXPECT_FALSE(bound.optimal);
    EXPECT_GE(bound.pairwise, bound.distance);
    const MinimumDistancePlan plan =
        plan_for(SamplingAlgorithm::Ual, DistanceStrategy::Hybrid, range);
    EXPECT_GE(plan.path_length, bound.pairwise - 0.05);  // up to the lattice
  }
}

TEST(MinimumDistance, IsDeterministicForASeed) {
  const MinimumDistancePlan first =
      plan_for(SamplingAlgorithm::Col, DistanceStrategy::Hybrid, 1.5, 7);
  const MinimumDistancePlan again =
      plan_for(SamplingAlgorithm::Col, DistanceStrategy::Hybrid, 1.5, 7);
  ASSERT_EQ(first.stops.size(), again.stops.size());
  for (std::size_t s = 0; s < first.stops.size(); ++s) {
    EXPECT_EQ(first.stops[s].point, again.stops[s].point);
  }
  EXPECT_EQ(first.path_length, again.path_length);
}

TEST(MinimumDistance, TwoThreadsPlanTheSamePathAsOne) {
  for (const SamplingAlgorithm algorithm : {SamplingAlgorithm::Col, SamplingAlgorithm::Ual}) {
    const MinimumDistancePlan one = plan_for(algorithm, DistanceStrategy::Weighted, 1.5, 3, 1);
    const MinimumDistancePlan two = plan_for(algorithm, DistanceStrategy::Weighted, 1.5, 3, 2);
    ASSERT_EQ(one.stops.size(), two.stops.size());
    for (std::size_t s = 0; s < one.stops.size(); ++s) {
      EXPECT_EQ(one.stops[s].point, two.stops[s].point);
      EXPECT_EQ(one.stops[s].value, two.stops[s].value);
    }
    EXPECT_EQ(one.path_length, two.path_length);
  }
}

TEST(MinimumDistance, OneHypothesisNeedsNoTravelAndBadOptionsAreRefused) {
  const Area map = test::comb_rooms();
  const std::vector<Pose2> one{{0.4, 3.0, 0.0}};
  const PolygonPlanningSpace space(map);
  const MinimumDistancePlan plan =
      localize_with_minimum_travel(space, one, perfect_sensing(map, one[0], one, kUnlimitedRange));
  EXPECT_TRUE(plan.resolved);
  EXPECT_TRUE(plan.stops.empty());
  EXPECT_EQ(plan.path_length, 0.0);
  EXPECT_THROW(localize_with_minimum_travel(space, {}, perfect_sensing(map, one[0], one, 1.0)),
               Error);
  EXPECT_THROW(PolygonPlanningSpace(map, {-1.0, 1e-6, 16}), Error);
  EXPECT_THROW(PolygonPlanningSpace(map, {std::nan(""), 1e-6, 16}), Error);
  MinimumDistanceOptions bad;
  bad.points = 0;
  EXPECT_THROW(validate(bad), Error);
  bad = {};
  bad.threads = 0;
  EXPECT_THROW(validate(bad), Error);
  EXPECT_THROW(travel_lower_bound(space, one), Error);
}

}  // namespace
}  // namespace gridloc
