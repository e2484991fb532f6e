// Tests of engine/src/evaluation/relations.cpp: the SLAM benchmark's relative-motion errors of scan
// matching, on a synthetic log whose relations are exact, and on bad input.
#include "gridloc/engine/evaluation/relations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "gridloc/sensors/segment_world.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

/// A 7 m x 4 m room with a box, a recess and a pillar: no symmetry to confuse a matcher.
std::vector<WallSegment> room() {
  auto box = [](double x0, double y0, double x1, double y1) {
    return std::vector<WallSegment>{
        {{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
  };
  std::vector<WallSegment> w = {{{0, 0}, {7, 0}},   {{7, 0}, {7, 4}},     {{7, 4}, {3, 4}},
                                {{3, 4}, {3, 4.6}}, {{3, 4.6}, {2, 4.6}}, {{2, 4.6}, {2, 4}},
                                {{2, 4}, {0, 4}},   {{0, 4}, {0, 0}}};
  for (const WallSegment& b : box(4.5, 1.0, 5.3, 1.6)) w.push_back(b);
  for (const WallSegment& b : box(1.0, 2.8, 1.3, 3.1)) w.push_back(b);
  return w;
}

/// A 360-beam scan (1 degree) from `pose`, exact ranges to the nearest wall.
RangeScan scan_at(const Pose2& pose) {
  return simulate_segment_scan(room(), pose, 360, -std::numbers::pi, std::numbers::pi / 180.0,
                               20.0);
}

/// A log of scans at `poses` and the exact relations between consecutive ones.
void synthetic(const std::vector<Pose2>& poses, CarmenLog& log, std::vector<RelationPair>& pairs) {
  for (std::size_t k = 0; k < poses.size(); ++k) {
    LaserRecord r;
    r.timestamp = static_cast<double>(k);
    r.scan = scan_at(poses[k]);
    r.laser_pose = r.robot_pose = poses[k];
    log.lasers.push_back(r);
    if (k > 0) {
      pairs.push_back({{static_cast<double>(k - 1), static_cast<double>(k),
                        relative_pose(poses[k - 1], poses[k]), k},
                       k - 1,
                       k});
    }
  }
}

TEST(RelationEval, RelativePose) {
  const Pose2 a{1.0, 2.0, std::numbers::pi / 2}, b{1.0, 3.0, std::numbers::pi};
  const Pose2 r = relative_pose(a, b);  // one metre ahead of a, turned left by 90 degrees
  EXPECT_NEAR(r.x, 1.0, 1e-12);
  EXPECT_NEAR(r.y, 0.0, 1e-12);
  EXPECT_NEAR(r.theta, std::numbers::pi / 2, 1e-12);
}

TEST(RelationEval, ScanReturnsDropNoReturn) {
  RangeScan s;
  s.max_range = 5.0;
  s.angles = {0.0, std::numbers::pi / 2, std::numbers::pi};
  s.ranges = {1.0, 5.0, 2.0};
  const auto p = scan_returns(s);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0].x(), 1.0, 1e-12);
  EXPECT_NEAR(p[1].x(), -2.0, 1e-12);
}

/// evaluate_relations by `matcher` on a synthetic log of exact relations, from priors off
/// by up to `noise_xy` (m) and `noise_theta` (rad).
RelationEvalReport synthetic_run(EstimatorKind matcher, double noise_xy, double noise_theta) {
  CarmenLog log;
  std::vector<RelationPair> pairs;
  synthetic({{2.0, 1.5, 0.1}, {2.3, 1.7, 0.25}, {2.6, 2.0, 0.2}, {2.5, 2.2, -0.1}}, log, pairs);
  RelationEvalOptions o;
  o.matcher = matcher;
  o.prior_noise_xy = noise_xy;
  o.prior_noise_theta = noise_theta;
  return evaluate_relations(log, pairs, o);
}

TEST(RelationEval, IcpRecoversExactRelationsFromANoisyPrior) {
  const RelationEvalReport r = synthetic_run(EstimatorKind::Icp, 0.05, 0.05);
  EXPECT_EQ(r.pairs, 3);
  EXPECT_EQ(r.failures, 0);
  EXPECT_LT(r.translation_error_m.mean, 1e-3);
  EXPECT_LT(r.rotation_error_deg.mean, 0.05);
}

TEST(RelationEval, CorrelationAndCorrelationIcpRecoverFarPriors) {
  // Priors off by up to 0.6 m and 20 deg: the correlation search finds the motion on the
  // lattice (5 cm, about 0.4 deg), ICP from there the exact one.
  const RelationEvalReport c = synthetic_run(EstimatorKind::Correlation, 0.6, 0.35);
  EXPECT_EQ(c.failures, 0);
  EXPECT_LT(c.translation_error_m.mean, 0.05);
  EXPECT_LT(c.rotation_error_deg.mean, 1.0);
  const RelationEvalReport ci = synthetic_run(EstimatorKind::CorrelationIcp, 0.6, 0.35);
  EXPECT_EQ(ci.failures, 0);
  EXPECT_LT(ci.translation_error_m.mean, 1e-3);
  EXPECT_LT(ci.rotation_error_deg.mean, 0.05);
}

TEST(RelationEval, Errors) {
  CarmenLog log;
  std::vector<RelationPair> pairs;
  test::expect_error([&] { evaluate_relations(log, pairs); }, {"no relation"});
  synthetic({{2.0, 1.5, 0.1}, {2.3, 1.7, 0.25}}, log, pairs);
  RelationEvalOptions sectors;
  sectors.matcher = EstimatorKind::Sectors;
  test::expect_error([&] { evaluate_relations(log, pairs, sectors); }, {"sectors", "polygon map"});
  pairs[0].second = 7;
  test::expect_error([&] { evaluate_relations(log, pairs); }, {"scan 7", "log of 2"});
}

}  // namespace
}  // namespace gridloc
