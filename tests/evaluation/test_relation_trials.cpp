// Tests of the relations protocol's per-pair trials, its size guard and its options' checks
// (engine/src/evaluation/relations.cpp, issue 13), on a synthetic log of exact relations.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "gridloc/engine/evaluation/calibration.hpp"
#include "gridloc/engine/evaluation/relations.hpp"
#include "gridloc/sensors/segment_world.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

/// A 7 m x 4 m room with a box and a pillar.
std::vector<WallSegment> room() {
  return {{{0, 0}, {7, 0}},         {{7, 0}, {7, 4}},       {{7, 4}, {0, 4}},
          {{0, 4}, {0, 0}},         {{4.5, 1}, {5.3, 1}},   {{5.3, 1}, {5.3, 1.6}},
          {{5.3, 1.6}, {4.5, 1.6}}, {{4.5, 1.6}, {4.5, 1}}, {{1, 2.8}, {1.3, 2.8}},
          {{1.3, 2.8}, {1.3, 3.1}}};
}

/// A log of 360-beam scans at `poses` and the exact relations between consecutive ones.
void synthetic(const std::vector<Pose2>& poses, CarmenLog& log, std::vector<RelationPair>& pairs) {
  for (std::size_t k = 0; k < poses.size(); ++k) {
    LaserRecord r;
    r.timestamp = static_cast<double>(k);
    r.scan = simulate_segment_scan(room(), poses[k], 360, -std::numbers::pi,
                                   std::numbers::pi / 180.0, 20.0);
    r.laser_pose = r.robot_pose = poses[k];
    log.lasers.push_back(r);
    if (k == 0) continue;
    pairs.push_back({{static_cast<double>(k - 1), static_cast<double>(k),
                      relative_pose(poses[k - 1], poses[k]), k},
                     k - 1,
                     k});
  }
}

class RelationTrials : public ::testing::Test {
 protected:
  void SetUp() override {
    synthetic({{2.0, 1.5, 0.1}, {2.3, 1.7, 0.25}, {2.6, 2.0, 0.2}, {2.5, 2.2, -0.1}}, log, pairs);
  }
  CarmenLog log;
  std::vector<RelationPair> pairs;
};

TEST_F(RelationTrials, OnePerPairAndTheTotalsFollowThem) {
  RelationEvalOptions o;
  o.matcher = EstimatorKind::CorrelationIcp;
  const RelationEvalReport r = evaluate_relations(log, pairs, o);
  ASSERT_EQ(r.trials.size(), 3u);
  double mean = 0.0;
  int failures = 0;
  for (std::size_t k = 0; k < r.trials.size(); ++k) {
    const RelationTrial& t = r.trials[k];
    EXPECT_EQ(t.pair, k);
    EXPECT_EQ(t.t1, static_cast<double>(k));
    EXPECT_EQ(t.t2, static_cast<double>(k + 1));
    EXPECT_NEAR(t.motion_m, std::hypot(pairs[k].relation.motion.x, pairs[k].relation.motion.y),
                1e-12);
    EXPECT_EQ(t.returns, 360);
    ASSERT_TRUE(t.verdict.has_value());
    EXPECT_TRUE(std::isfinite(t.confidence));
    EXPECT_TRUE(t.refined);  // ICP's pose kept: exact relations
    EXPECT_GT(t.search_cells, 0u);
    EXPECT_LT(t.translation_error_m, 1e-3);
    mean += t.translation_error_m / 3.0;
    failures += t.failed ? 1 : 0;
  }
  EXPECT_EQ(r.failures, failures);
  EXPECT_NEAR(r.translation_error_m.mean, mean, 1e-15);
}

TEST_F(RelationTrials, TablesCountEveryPairByOverlapAndVerdict) {
  RelationEvalOptions o;
  o.matcher = EstimatorKind::Correlation;
  const RelationEvalReport r = evaluate_relations(log, pairs, o);
  int localized = 0;
  for (const RelationTrial& t : r.trials) {
    EXPECT_GT(t.overlap, 0.9);  // a room seen twice
    EXPECT_GT(t.answer_overlap, 0.9);
    EXPECT_EQ(t.truth.x, pairs[t.pair].relation.motion.x);
    EXPECT_GT(t.covariance(0, 0), 0.0);
    localized += t.verdict == Verdict::Localized;
  }
  EXPECT_EQ(r.calibration.localized, localized);
  EXPECT_EQ(r.covered_failures, 0);
  ASSERT_EQ(r.failures_by_overlap.size(), 5u);
  EXPECT_EQ(r.failures_by_overlap.back().label, "0.8-1");
  EXPECT_EQ(r.failures_by_overlap.back().pairs, 3);
  EXPECT_EQ(r.overlapping.pairs, 3);
  EXPECT_EQ(r.overlapping.failures, r.failures);
  int pairs_by_verdict = 0, failures_by_verdict = 0;
  for (const FailureRow& row : r.failures_by_verdict) {
    EXPECT_NE(row.label, "none");
    pairs_by_verdict += row.pairs;
    failures_by_verdict += row.failures;
  }
  EXPECT_EQ(pairs_by_verdict, 3);
  EXPECT_EQ(failures_by_verdict, r.failures);
  // ICP alone has one row, "none"; pairs overlapping less than asked are left out.
  RelationEvalOptions icp;
  icp.overlapping_share = 1.0;
  const RelationEvalReport i = evaluate_relations(log, pairs, icp);
  ASSERT_EQ(i.failures_by_verdict.size(), 1u);
  EXPECT_EQ(i.failures_by_verdict[0].label, "none");
  EXPECT_EQ(i.failures_by_verdict[0].pairs, 3);
  EXPECT_LT(i.overlapping.pairs, 3);
}

/// A straight corridor 2 m wide, longer than the laser reaches: nothing along it to pin a
/// scan.
std::vector<WallSegment> corridor() {
  return {{{-40, -1}, {40, -1}}, {{-40, 1}, {40, 1}}};
}

/// A 181-beam front laser (20 m) at `pose` among `walls`.
RangeScan front_scan(const std::vector<WallSegment>& walls, const Pose2& pose) {
  return simulate_segment_scan(walls, pose, 181, -0.5 * std::numbers::pi, std::numbers::pi / 180.0,
                               20.0);
}

TEST(RelationCorridor, AnAnswerSlidAlongTheCorridorSaysSo) {
  // Two scans 0.5 m apart along the corridor; the prior off by 0.25 m along it. Any pose
  // along the corridor fits as well: the answer is either not `localized` or its 2-sigma
  // ellipse covers its error, and the ellipse lies along the corridor.
  const Pose2 first{0.0, 0.1, 0.0}, second{0.5, 0.1, 0.05};
  const auto scan_at = [](const Pose2& pose) { return front_scan(corridor(), pose); };
  const Pose2 truth = relative_pose(first, second);
  RelationEvalOptions options;
  options.matcher = EstimatorKind::Correlation;
  for (double slide : {-0.25, 0.25}) {
    const Pose2 prior{truth.x + slide, truth.y + 0.03, truth.theta - 0.02};
    const PairMatch m = match_relation_pair(scan_at(first), scan_at(second), prior, options);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(m.covariance.topLeftCorner<2, 2>());
    const Eigen::Vector2d along = axes.eigenvectors().col(1);  // the major axis
    const double sigma_along = std::sqrt(axes.eigenvalues()(1));
    const Eigen::Vector2d error(m.pose.x - truth.x, m.pose.y - truth.y);
    EXPECT_GT(std::abs(along.x()), 0.99) << slide;  // the ellipse lies along the corridor
    EXPECT_TRUE(m.verdict != Verdict::Localized || std::abs(error.dot(along)) <= 2 * sigma_along)
        << "slide " << slide << ": " << error.x() << " m off along, sigma " << sigma_along;
    EXPECT_LT(std::abs(error.y()), 0.05) << slide;  // across: pinned to a cell
  }
}

/// The same corridor with its walls broken every 0.35 m (0.25 m of wall, 0.1 m of door):
/// poses a period apart fit about alike, as separate peaks.
std::vector<WallSegment> corridor_with_doors() {
  std::vector<WallSegment> walls;
  for (double x = -20.0; x < 20.0; x += 0.35) {
    walls.push_back({{x, -1}, {x + 0.25, -1}});
    walls.push_back({{x, 1}, {x + 0.25, 1}});
  }
  return walls;
}

TEST(RelationCorridor, TheCovarianceSpansTheCorridorsOtherPeaks) {
  // The prior a period off along the corridor: the window holds peaks a period apart, and a
  // covariance read around the winner alone cannot cover a period's error.
  const Pose2 first{0.0, 0.1, 0.0}, second{0.5, 0.1, 0.0};
  const auto scan_at = [](const Pose2& pose) { return front_scan(corridor_with_doors(), pose); };
  const Pose2 truth = relative_pose(first, second);
  RelationEvalOptions options;
  options.matcher = EstimatorKind::Correlation;
  ASSERT_TRUE(options.correlation.covariance_spans_peaks);  // the relations protocol's default
  RelationEvalOptions winner_only = options;
  winner_only.correlation.covariance_spans_peaks = false;
  const auto sigma_along = [](const PairMatch& m) { return std::sqrt(m.covariance(0, 0)); };
  for (double slide : {-0.35, 0.35}) {
    const Pose2 prior{truth.x + slide, truth.y + 0.02, truth.theta};
    const PairMatch spanning = match_relation_pair(scan_at(first), scan_at(second), prior, options);
    const PairMatch narrow =
        match_relation_pair(scan_at(first), scan_at(second), prior, winner_only);
    EXPECT_EQ(spanning.pose.x, narrow.pose.x) << slide;  // reported covariance only
    EXPECT_EQ(spanning.pose.y, narrow.pose.y) << slide;
    EXPECT_EQ(spanning.verdict, narrow.verdict) << slide;
    EXPECT_GT(sigma_along(spanning), 2.0 * sigma_along(narrow)) << slide;
    EXPECT_GT(2.0 * sigma_along(spanning), 0.35 / 2) << slide;  // half a period, at least
    const double error = std::abs(spanning.pose.x - truth.x);
    EXPECT_TRUE(spanning.verdict != Verdict::Localized || error <= 2.0 * sigma_along(spanning))
        << "slide " << slide << ": " << error << " m off along, sigma " << sigma_along(spanning);
    EXPECT_LT(std::sqrt(spanning.covariance(1, 1)), 0.1) << slide;  // across: still pinned
  }
}

TEST_F(RelationTrials, IcpFromThePriorTooKeepsExactRelations) {
  RelationEvalOptions o;
  o.matcher = EstimatorKind::CorrelationIcp;
  o.icp_from_prior = true;
  const RelationEvalReport r = evaluate_relations(log, pairs, o);
  EXPECT_EQ(r.failures, 0);
  EXPECT_LT(r.translation_error_m.mean, 1e-3);
}

TEST_F(RelationTrials, IcpTrialsHaveNoVerdict) {
  const RelationEvalReport r = evaluate_relations(log, pairs, {});
  ASSERT_EQ(r.trials.size(), 3u);
  for (const RelationTrial& t : r.trials) {
    EXPECT_FALSE(t.verdict.has_value());
    EXPECT_TRUE(std::isnan(t.confidence));
    EXPECT_EQ(t.search_cells, 0u);
    EXPECT_TRUE(t.converged);
  }
}

TEST_F(RelationTrials, MatchPairIsMatchRelationPair) {
  RelationEvalOptions o;
  o.matcher = EstimatorKind::Correlation;
  const Pose2 prior{0.3, 0.15, 0.1};
  bool converged = false;
  const Pose2 p = match_pair(log.lasers[0].scan, log.lasers[1].scan, prior, o, &converged);
  const PairMatch m = match_relation_pair(log.lasers[0].scan, log.lasers[1].scan, prior, o);
  EXPECT_TRUE(converged);
  EXPECT_EQ(p.x, m.pose.x);
  EXPECT_EQ(p.y, m.pose.y);
  EXPECT_EQ(p.theta, m.pose.theta);
}

TEST_F(RelationTrials, ExhaustiveAndBranchAndBoundAgree) {
  RelationEvalOptions exhaustive, bnb;
  exhaustive.matcher = bnb.matcher = EstimatorKind::Correlation;
  bnb.correlation.strategy = SearchStrategy::BranchAndBound;
  EXPECT_EQ(exhaustive.correlation.strategy, SearchStrategy::Exhaustive);
  const RelationEvalReport a = evaluate_relations(log, pairs, exhaustive);
  const RelationEvalReport b = evaluate_relations(log, pairs, bnb);
  for (std::size_t k = 0; k < a.trials.size(); ++k) {
    EXPECT_EQ(a.trials[k].translation_error_m, b.trials[k].translation_error_m) << k;
    EXPECT_EQ(a.trials[k].rotation_error_deg, b.trials[k].rotation_error_deg) << k;
    EXPECT_EQ(a.trials[k].verdict, b.trials[k].verdict) << k;
  }
}

TEST_F(RelationTrials, ASearchTooLargeIsRefusedNamingThePairAndTheSize) {
  RelationEvalOptions o;
  o.matcher = EstimatorKind::Correlation;
  o.max_search_mb = 0.5;
  test::expect_error([&] { evaluate_relations(log, pairs, o); },
                     {"relations: pair 0 (t1 0.000 s, t2 1.000 s)", "MB", "cells of 0.05 m",
                      "max_search_mb = 0.5"});
  // Branch and bound's pyramid makes the same pair about ten times larger.
  o.max_search_mb = 5.0;
  EXPECT_NO_THROW(evaluate_relations(log, pairs, o));
  o.correlation.strategy = SearchStrategy::BranchAndBound;
  test::expect_error([&] { evaluate_relations(log, pairs, o); }, {"pair 0", "max_search_mb = 5"});
}

TEST_F(RelationTrials, BadOptionsNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto expect_bad = [&](auto change, const char* field) {
    RelationEvalOptions o;
    change(o);
    test::expect_error([&] { validate(o); }, {field});
    test::expect_error([&] { evaluate_relations(log, pairs, o); }, {field});
  };
  expect_bad([](RelationEvalOptions& o) { o.prior_noise_xy = -0.1; }, "prior_noise_xy");
  expect_bad([&](RelationEvalOptions& o) { o.prior_noise_theta = nan; }, "prior_noise_theta");
  expect_bad([](RelationEvalOptions& o) { o.failure_xy = 0.0; }, "failure_xy");
  expect_bad([](RelationEvalOptions& o) { o.map_resolution = -0.05; }, "map_resolution");
  expect_bad([](RelationEvalOptions& o) { o.window_margin_theta = -1.0; }, "window_margin_theta");
  expect_bad([&](RelationEvalOptions& o) { o.refine_max_shift_m = nan; }, "refine_max_shift_m");
  expect_bad([](RelationEvalOptions& o) { o.max_search_mb = 0.0; }, "max_search_mb");
  expect_bad([](RelationEvalOptions& o) { o.overlap_radius_m = 0.0; }, "overlap_radius_m");
  expect_bad([](RelationEvalOptions& o) { o.join_gap_m = -0.1; }, "join_gap_m");
  expect_bad([](RelationEvalOptions& o) { o.join_grazing_rad = 1.6; }, "join_grazing_rad");
  expect_bad([](RelationEvalOptions& o) { o.overlapping_share = 1.5; }, "overlapping_share");
  expect_bad([](RelationEvalOptions& o) { o.overlap_band_edges = {0.5, 0.5}; }, "overlap bands");
  EXPECT_NO_THROW(validate(RelationEvalOptions{}));
}

}  // namespace
}  // namespace gridloc
