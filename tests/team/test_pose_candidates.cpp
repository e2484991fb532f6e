// Candidate configurations (seed 003 ch. III A-B): a robot's features placed on a square's
// and the T's corners and walls, and the scan check that drops placements the scan disagrees
// with.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "gridloc/engine/team/pose_candidates.hpp"
#include "gridloc/sensors/rotating_ir.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

PolygonMap square() {
  return make_polygon_map({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, {});
}

PolygonMap t_shape() {
  return make_polygon_map(
      {{0, 0}, {1.5, 0}, {1.5, 1.0}, {3.0, 1.0}, {3.0, 2.75}, {1.5, 2.75}, {1.5, 3.75}, {0, 3.75}},
      {});
}

RangeScan exact_scan(const PolygonMap& map, const Pose2& pose, double range = 0.3) {
  IrSensorOptions ir;
  ir.noise = false;
  ir.smoothing_half_window = 0;
  ir.max_range_m = range;
  return simulate_ir_scan(map, pose, ir, 1);
}

bool has_pose(const std::vector<PoseCandidate>& candidates, const Pose2& pose) {
  for (const PoseCandidate& c : candidates) {
    const bool heading = std::abs(normalize_angle(c.pose.theta - pose.theta)) < 0.01;
    if (!c.segment() && heading && std::hypot(c.pose.x - pose.x, c.pose.y - pose.y) < 0.005)
      return true;
    if (c.segment() && heading) {  // on the segment
      const Eigen::Vector2d p(pose.x, pose.y);
      const double t = std::clamp((p - c.position()).dot(c.along), 0.0, c.length);
      if ((c.position(t) - p).norm() < 0.005) return true;
    }
  }
  return false;
}

TEST(PoseCandidates, AConcaveCornerGoesInEveryCornerOfASquare) {
  const PolygonMap map = square();
  const MapFeatures features = polygon_features(map);
  const Pose2 truth{0.1, 0.15, 0.3};
  const RangeScan scan = exact_scan(map, truth);
  const auto found = extract_features(scan);
  ASSERT_FALSE(found.empty());
  ASSERT_EQ(found.front().kind, FeatureKind::ConcaveCorner);
  CandidateOptions every;
  every.min_agreement = 0.0;  // the thesis's method: every placement
  const auto candidates = feature_candidates(found.front(), 0, features, every);
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_TRUE(has_pose(candidates, truth));
  // The square turned by a quarter about its centre (1, 1) carries the truth to each corner.
  for (int k = 1; k < 4; ++k) {
    const double turn = k * kPi / 2;
    const Eigen::Vector2d p = Eigen::Rotation2Dd(turn) * Eigen::Vector2d(truth.x - 1, truth.y - 1);
    EXPECT_TRUE(has_pose(candidates, {1 + p.x(), 1 + p.y(), normalize_angle(truth.theta + turn)}))
        << "corner " << k;
  }
}

TEST(PoseCandidates, TheTsCornersAndWalls) {
  const PolygonMap map = t_shape();
  const MapFeatures features = polygon_features(map);
  CandidateOptions every;
  every.min_agreement = 0.0;
  // A concave corner: the T's six; a convex corner seen on both walls: its two.
  const Pose2 in_corner{1.3, 0.2, 2.0};
  const auto concave = extract_features(exact_scan(map, in_corner));
  ASSERT_EQ(concave.front().kind, FeatureKind::ConcaveCorner);
  EXPECT_EQ(feature_candidates(concave.front(), 0, features, every).size(), 6u);
  const Pose2 by_convex{1.35, 1.15, 0.5};
  const auto convex = extract_features(exact_scan(map, by_convex));
  ASSERT_EQ(convex.front().kind, FeatureKind::ConvexCorner);
  const auto two = feature_candidates(convex.front(), 0, features, every);
  EXPECT_EQ(two.size(), 2u);
  EXPECT_TRUE(has_pose(two, by_convex));
  // A wall: a segment along each of the 8 walls, the truth on the one it faces.
  const Pose2 by_wall{0.15, 2.0, 1.0};
  const auto wall = extract_features(exact_scan(map, by_wall));
  ASSERT_EQ(wall.size(), 1u);
  ASSERT_EQ(wall.front().kind, FeatureKind::Wall);
  const auto segments = feature_candidates(wall.front(), 0, features, every);
  EXPECT_EQ(segments.size(), 8u);
  for (const PoseCandidate& c : segments) EXPECT_TRUE(c.segment());
  EXPECT_TRUE(has_pose(segments, by_wall));
}

TEST(PoseCandidates, TheScanCheckDropsPlacementsTheScanDisagreesWith) {
  // In the T's corner (0, 0), 0.1 m from both walls: within 0.3 m all six concave corners read
  // alike and every placement stays; a 2.5 m sensor sees the rest of the room.
  const PolygonMap map = t_shape();
  const MapFeatures features = polygon_features(map);
  const Pose2 truth{0.1, 0.1, 0.7};
  const RangeScan near = exact_scan(map, truth, 0.3);
  EXPECT_EQ(robot_candidates(near, extract_features(near), features).size(), 6u);
  const RangeScan far = exact_scan(map, truth, 2.5);
  // At 2.5 m every other corner has 7-27 % of the readings off by more than 3 cm.
  CandidateOptions strict;
  strict.min_agreement = 0.95;
  const auto kept = robot_candidates(far, extract_features(far), features, strict);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_TRUE(has_pose(kept, truth));
  EXPECT_GT(scan_agreement(far, truth, features, 0.03), 0.99);
}

TEST(PoseCandidates, RefusesBadOptions) {
  CandidateOptions options;
  options.features = 0;
  test::expect_error([&] { validate(options); }, {"features"});
  options = {};
  options.min_agreement = 1.5;
  test::expect_error([&] { validate(options); }, {"min_agreement"});
}

}  // namespace
}  // namespace gridloc
