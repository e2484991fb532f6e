// Tests of the search run a budget at a time (issue 34: a tracker's re-search spread over its
// updates): ResumableBranchAndBound against the exhaustive search, exactly, whatever the
// budget, with its progress; PendingEstimate against CorrelationEstimator::estimate().
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <tuple>

#include "correlation/scan_cases.hpp"
#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/engine/correlation/pending_estimate.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "localizer/laser_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;  // the shared search cases and checks

TEST(ResumableBranchAndBound, EqualsTheWholeSearchWhateverTheBudget) {
  std::mt19937 rng(3417);
  int resumed = 0, kept = 0;
  for (int c = 0; c < 160; ++c) {
    const ScanCase s = make_scan_case(rng, c);
    const PaddedGrid padded = pad_grid(s.grid, s.pad, s.rule);
    const BoundPyramid pyramid = make_bound_pyramid(
        padded, s.depth, c % 3 == 0 ? PyramidLevels::MaxAndMin : PyramidLevels::MaxOnly);
    const SearchLevel level = points_level(padded, s.points);
    const SearchResult all = search_exhaustive(s.lat, level);
    const HeadingGrids grids(s.lat, level);
    BranchAndBoundOptions options;
    options.heading_intervals = c % 2 == 0;
    options.keep_share = c % 4 < 2 ? 0.9 : 1.0;
    if (c % 8 == 1) options.keep_outside = Exclusion{{}, 2.5, 1, 0.0};
    ResumableBranchAndBound search(s.lat, grids, pyramid, options);
    // Not done before it ran (a lattice too small for bound levels is searched at once).
    if (!search.done()) {
      EXPECT_THROW(search.take_result(), Error) << s.what;
    }
    // A budget of a few bounds an advance: the search stops and resumes many times.
    const long long budget = 1 + static_cast<long long>(s.points.size()) * (c % 3);
    int advances = 0;
    double open = search.open_share();
    EXPECT_LE(open, 1.0);
    while (!search.advance(budget)) {
      ++advances;
      const double now = search.open_share();
      EXPECT_LE(now, open + 1e-12) << s.what << ": the open share grew";
      open = now;
      ASSERT_LT(advances, 10000000) << s.what;
    }
    EXPECT_EQ(search.open_share(), 0.0);
    resumed += advances > 3 ? 1 : 0;
    const SearchResult r = search.take_result();
    expect_pose(r.best, all.best, s.what);
    EXPECT_TRUE(r.proven_optimal) << s.what;
    if (options.keep_share >= 1.0 || all.best.score <= 0.0) continue;
    std::set<std::tuple<int, int, int>> scored;
    for (const LatticePose& p : r.scored) scored.insert({p.ix, p.iy, p.it});
    Exclusion around_best = options.keep_outside.value_or(Exclusion{});
    around_best.center = all.best;
    for (const LatticePose& p : all.scored) {
      if (p.score < options.keep_share * all.best.score) continue;
      if (options.keep_outside && around_best.contains(p.ix, p.iy, p.it)) continue;
      EXPECT_TRUE(scored.count({p.ix, p.iy, p.it})) << s.what << ": a pose within the share";
      ++kept;
    }
  }
  EXPECT_GT(resumed, 80);  // most searches ran over several advances
  EXPECT_GT(kept, 80);
}

/// Every field of two estimates a reader uses, equal.
void expect_same_estimate(const Estimate& a, const Estimate& b, const std::string& what) {
  EXPECT_EQ(a.pose.x, b.pose.x) << what;
  EXPECT_EQ(a.pose.y, b.pose.y) << what;
  EXPECT_EQ(a.pose.theta, b.pose.theta) << what;
  EXPECT_EQ(a.score, b.score) << what;
  EXPECT_EQ(a.normalized_score, b.normalized_score) << what;
  EXPECT_EQ(a.second_score, b.second_score) << what;
  EXPECT_EQ(a.verdict, b.verdict) << what;
  EXPECT_EQ(a.covariance, b.covariance) << what;
  ASSERT_EQ(a.alternatives.size(), b.alternatives.size()) << what;
  for (std::size_t k = 0; k < a.alternatives.size(); ++k) {
    EXPECT_EQ(a.alternatives[k].pose.x, b.alternatives[k].pose.x) << what << " " << k;
    EXPECT_EQ(a.alternatives[k].pose.y, b.alternatives[k].pose.y) << what << " " << k;
    EXPECT_EQ(a.alternatives[k].pose.theta, b.alternatives[k].pose.theta) << what << " " << k;
    EXPECT_EQ(a.alternatives[k].score, b.alternatives[k].score) << what << " " << k;
  }
}

TEST(PendingEstimate, AnswersAsTheWholeEstimateDoes) {
  const OccupancyMap map = two_rooms();  // two identical rooms: look-alikes to report
  int compared = 0;
  for (const double floor : {0.9, 0.0}) {  // the hypotheses in one search, or one search each
    CorrelationOptions options;
    options.resolution = 0.05;
    options.reach_m = 7.0;
    options.second_peak_floor = floor;
    const CorrelationEstimator estimator(map, options);
    for (const Pose2& truth :
         {Pose2{3.0, 5.5, 0.3}, Pose2{9.5, 5.0, -2.0}, Pose2{12.0, 3.0, 0.0}}) {
      Observation observation;
      observation.scan = simulate_scan(map, truth, 180, 6.0, 0.0, 1);
      const SearchWindow global = estimator.global_window(observation);
      const Estimate whole = estimator.estimate(observation, global, 5);
      PendingEstimate pending(estimator, observation, global, 5);
      EXPECT_THROW(pending.result(), Error);
      int advances = 1;
      while (!pending.advance(20000)) ++advances;
      EXPECT_GT(advances, 3);  // the search ran over several advances
      EXPECT_TRUE(pending.done());
      const std::string what = "floor " + std::to_string(floor) + " at " + std::to_string(truth.x) +
                               ", " + std::to_string(truth.y);
      expect_same_estimate(pending.result(), whole, what);
      const PendingEstimate copy = pending;  // copies share the one search and its answer
      expect_same_estimate(copy.result(), whole, what + " (copy)");
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6);
}

TEST(PendingEstimate, ChecksItsInputsAsTheEstimateDoes) {
  const OccupancyMap map = two_rooms();
  CorrelationOptions options;
  options.resolution = 0.05;
  options.reach_m = 7.0;
  const CorrelationEstimator estimator(map, options);
  Observation observation;
  observation.scan = simulate_scan(map, {3.0, 5.5, 0.0}, 180, 6.0, 0.0, 1);
  SearchWindow window = estimator.global_window(observation);
  EXPECT_THROW(PendingEstimate(estimator, observation, window, 0), Error);
  window.step_xy = 0.1;  // not the map's cell
  EXPECT_THROW(PendingEstimate(estimator, observation, window, 1), Error);
}

}  // namespace
}  // namespace gridloc
