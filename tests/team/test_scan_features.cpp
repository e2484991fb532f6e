// Tests of engine/src/team/scan_features.cpp and feature_offsets.cpp: the corners and walls of
// hand-made short-range scans (exact ray casting against wall segments, once with noise), and
// seed 003's offsets, which must give the map-frame vector from the robot to the feature.
#include "gridloc/engine/team/scan_features.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "gridloc/sensors/segment_world.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

/// A 360-beam scan of `walls` from `pose`, beam k at first_deg + k degrees.
RangeScan scan_of(const std::vector<WallSegment>& walls, double max_range, const Pose2& pose = {},
                  double first_deg = 0.0) {
  return simulate_segment_scan(walls, pose, 360, first_deg * kDeg, kDeg, max_range);
}

Eigen::Vector2d rotated(const Eigen::Vector2d& v, double theta) {
  return {std::cos(theta) * v.x() - std::sin(theta) * v.y(),
          std::sin(theta) * v.x() + std::cos(theta) * v.y()};
}

int returns_of(const RangeScan& scan) {
  int n = 0;
  for (double r : scan.ranges) n += r < scan.max_range;
  return n;
}

void expect_near(const Eigen::Vector2d& got, const Eigen::Vector2d& want, double tol) {
  EXPECT_LE((got - want).norm(), tol) << "got (" << got.x() << ", " << got.y() << "), want ("
                                      << want.x() << ", " << want.y() << ")";
}

/// The world frame's copy of the scene seen from the origin: every point placed by `pose`.
std::vector<WallSegment> placed(const std::vector<WallSegment>& walls, const Pose2& pose) {
  const Eigen::Vector2d t(pose.x, pose.y);
  std::vector<WallSegment> out;
  for (const WallSegment& w : walls) {
    out.push_back({t + rotated(w.a, pose.theta), t + rotated(w.b, pose.theta)});
  }
  return out;
}

// A concave 90 deg corner 0.15 m ahead and 0.1 m to the right: the wall y = -0.1 running +x
// into the corner (0.15, -0.1), the wall x = 0.15 leaving it along +y. Its run crosses the
// scan's seam (angle 0).
const std::vector<WallSegment> kConcave{{{-1, -0.1}, {0.15, -0.1}}, {{0.15, -0.1}, {0.15, 1}}};

TEST(ScanFeatures, ConcaveCornerIsTheFittedWallsIntersection) {
  const RangeScan scan = scan_of(kConcave, 0.3);
  const auto features = extract_features(scan);
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::ConcaveCorner);
  expect_near(f.point, {0.15, -0.1}, 0.002);
  EXPECT_NEAR(f.free_angle, kPi / 2, 1e-6);
  expect_near(f.wall1, {1, 0}, 1e-9);  // arrives along the scan, the robot on its left
  expect_near(f.wall2, {0, 1}, 1e-9);
  EXPECT_EQ(f.points, returns_of(scan));  // every return lies on one of the two walls
  EXPECT_LT(f.fit_rms_m, 1e-9);
  // The walls' ends at the max range: the first on y = -0.1, the last on x = 0.15.
  EXPECT_NEAR(f.saturation1.y(), -0.1, 1e-9);
  EXPECT_NEAR(f.saturation2.x(), 0.15, 1e-9);
  EXPECT_GT(f.saturation1.norm(), 0.285);
  EXPECT_GT(f.saturation2.norm(), 0.285);
  // The offsets are the perpendiculars from the robot to both walls.
  const FeatureOffsets o = feature_offsets(f);
  expect_near(o.offset1, {0, -0.1}, 0.002);
  expect_near(o.offset2, {0.15, 0}, 0.002);
  EXPECT_NEAR(o.offset1.norm(), 0.1, 0.002);
  EXPECT_NEAR(o.offset2.norm(), 0.15, 0.002);
}

TEST(ScanFeatures, ConcaveCornerWithSmoothedNoise) {
  RangeScan scan = scan_of(kConcave, 0.3);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.003);
  for (double& r : scan.ranges) {
    if (r < scan.max_range) r += noise(rng);
  }
  // Seed 003 ch. VI B filters the raw scan with a moving average (there five readings either
  // side; two here, over returns only).
  const std::vector<double> raw = scan.ranges;
  const int n = static_cast<int>(raw.size());
  for (int k = 0; k < n; ++k) {
    if (raw[k] >= scan.max_range) continue;
    double sum = 0.0;
    int count = 0;
    for (int j = k - 2; j <= k + 2; ++j) {
      const double r = raw[(j + n) % n];
      if (r < scan.max_range) sum += r, ++count;
    }
    scan.ranges[k] = sum / count;
  }
  const auto features = extract_features(scan);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features[0].kind, FeatureKind::ConcaveCorner);
  expect_near(features[0].point, {0.15, -0.1}, 0.005);
  EXPECT_NEAR(features[0].free_angle, kPi / 2, 0.05);
  EXPECT_GT(features[0].fit_rms_m, 1e-4);  // the noise shows in the fit
  EXPECT_LT(features[0].fit_rms_m, 0.003);
}

TEST(ScanFeatures, ConvexCornerWithBothWallsSeen) {
  // The corner (0.1, 0.1) of a block filling x >= 0.1, y >= 0.1: its face y = 0.1 runs -x in
  // scan order into the corner, its face x = 0.1 leaves it along +y (a right turn).
  const std::vector<WallSegment> walls{{{1, 0.1}, {0.1, 0.1}}, {{0.1, 0.1}, {0.1, 1}}};
  const auto features = extract_features(scan_of(walls, 0.3));
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::ConvexCorner);
  expect_near(f.point, {0.1, 0.1}, 0.002);
  EXPECT_NEAR(f.free_angle, 1.5 * kPi, 1e-6);
  expect_near(f.wall1, {-1, 0}, 1e-9);
  expect_near(f.wall2, {0, 1}, 1e-9);
  const FeatureOffsets o = feature_offsets(f);
  expect_near(o.offset1, {0, 0.1}, 0.002);
  expect_near(o.offset2, {0.1, 0}, 0.002);
}

TEST(ScanFeatures, ConvexCornerWithOneWallWhereTheWallArrives) {
  // The wall y = -0.1 ends at (0.1, -0.1); the corner's other wall x = 0.1 goes away from the
  // robot, hidden. Beams at 0.3 + k deg: the last return falls 2.4 mm short of the corner.
  const std::vector<WallSegment> walls{{{-1, -0.1}, {0.1, -0.1}}, {{0.1, -0.1}, {0.1, -1}}};
  const auto features = extract_features(scan_of(walls, 0.3, {}, 0.3));
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::ConvexCornerOneWall);
  EXPECT_TRUE(f.seen_wall_arrives);
  EXPECT_NEAR(f.point.y(), -0.1, 1e-9);  // on the fitted wall
  EXPECT_LE(f.point.x(), 0.1);
  EXPECT_GT(f.point.x(), 0.1 - 0.003);  // within a beam step of the corner
  expect_near(f.wall1, {1, 0}, 1e-9);
  EXPECT_EQ(f.wall2, Eigen::Vector2d::Zero());
  expect_near(f.saturation2, f.point, 1e-12);  // the wall's last point is the corner
  EXPECT_GT(f.saturation1.norm(), 0.285);      // its first a saturation point
  const FeatureOffsets o = feature_offsets(f);
  expect_near(o.offset1, {0, -0.1}, 1e-9);         // normal to the wall (eq. 3.20)
  expect_near(o.offset2, {f.point.x(), 0}, 1e-9);  // along it (eq. 3.21)
}

TEST(ScanFeatures, ConvexCornerWithOneWallWhereTheWallLeaves) {
  // Mirrored: the wall y = -0.1 starts at the corner (-0.1, -0.1) behind a jump.
  const std::vector<WallSegment> walls{{{-0.1, -0.1}, {1, -0.1}}, {{-0.1, -0.1}, {-0.1, -1}}};
  const auto features = extract_features(scan_of(walls, 0.3, {}, 0.3));
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::ConvexCornerOneWall);
  EXPECT_FALSE(f.seen_wall_arrives);
  EXPECT_NEAR(f.point.y(), -0.1, 1e-9);
  EXPECT_GE(f.point.x(), -0.1);
  EXPECT_LT(f.point.x(), -0.1 + 0.003);
  expect_near(f.wall1, {1, 0}, 1e-9);
  expect_near(f.saturation1, f.point, 1e-12);
  EXPECT_GT(f.saturation2.norm(), 0.285);
}

TEST(ScanFeatures, WallBetweenSaturationPoints) {
  const std::vector<WallSegment> walls{{{-1, -0.1}, {1, -0.1}}};
  const auto features = extract_features(scan_of(walls, 0.3));
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::Wall);
  expect_near(f.point, {0, -0.1}, 1e-9);  // the foot of the perpendicular
  expect_near(f.wall1, {1, 0}, 1e-9);
  EXPECT_LT(f.saturation1.x(), -0.25);
  EXPECT_GT(f.saturation2.x(), 0.25);
  const FeatureOffsets o = feature_offsets(f);
  expect_near(o.offset1, {0, -0.1}, 1e-9);
  EXPECT_NEAR(o.offset1.norm(), 0.1, 1e-9);
  EXPECT_EQ(o.offset2, Eigen::Vector2d::Zero());
}

TEST(ScanFeatures, GlancingWallRunningOutOfRangeIsNoCorner) {
  // A wall 4 cm away: at the max range the beams meet it so obliquely that its last returns
  // lie 1.4 and 2.9 cm short of the max range, more than saturation_margin_m; the wall's line
  // would only meet the next beam beyond the max range, so these ends are saturation points.
  const std::vector<WallSegment> walls{{{-1, -0.04}, {1, -0.04}}};
  const RangeScan scan = scan_of(walls, 0.3, {}, 0.5);
  double last_of_run = 0.0;  // the return just before the first saturated reading past it
  for (std::size_t k = 1; k < scan.ranges.size(); ++k) {
    if (scan.ranges[k - 1] < scan.max_range && scan.ranges[k] >= scan.max_range) {
      last_of_run = scan.ranges[k - 1];
    }
  }
  ASSERT_LT(last_of_run, scan.max_range - FeatureOptions{}.saturation_margin_m);
  const auto features = extract_features(scan);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features[0].kind, FeatureKind::Wall);
  expect_near(features[0].point, {0, -0.04}, 1e-9);
}

TEST(ScanFeatures, AJumpNearerIsNoCornerOfTheHiddenWall) {
  // A pillar face y = -0.1, x in [-0.03, 0.03], in front of the wall y = -0.2. The wall's runs
  // end where the pillar hides them (jumps nearer: no corner of the wall); the pillar's ends
  // jump farther: two convex corners with one wall each.
  const std::vector<WallSegment> walls{{{-1, -0.2}, {1, -0.2}}, {{-0.03, -0.1}, {0.03, -0.1}}};
  const auto features = extract_features(scan_of(walls, 0.3, {}, 0.5));
  ASSERT_EQ(features.size(), 4u);
  EXPECT_EQ(features[0].kind, FeatureKind::ConvexCornerOneWall);
  EXPECT_EQ(features[1].kind, FeatureKind::ConvexCornerOneWall);
  EXPECT_FALSE(features[0].seen_wall_arrives);  // equally near: scan order kept
  expect_near(features[0].point, {-0.03, -0.1}, 0.003);
  EXPECT_TRUE(features[1].seen_wall_arrives);
  expect_near(features[1].point, {0.03, -0.1}, 0.003);
  for (int i : {2, 3}) {
    EXPECT_EQ(features[i].kind, FeatureKind::Wall);
    expect_near(features[i].point, {0, -0.2}, 1e-9);
  }
  EXPECT_LT(features[2].saturation2.x(), -0.05);  // the left piece, up to the pillar's shadow
  EXPECT_GT(features[3].saturation1.x(), 0.05);
}

TEST(ScanFeatures, WallsWhoseLinesMeetFarFromThemAreNoCorner) {
  // The wall y = -0.1 up to x = 0, a 4 cm step down (along the beam, unseen), and a wall
  // turning left by 25 deg from (0, -0.14): one run, but the lines meet 8.6 cm from the first
  // wall's end, farther than gap_m.
  const Eigen::Vector2d b(0, -0.14), out(std::cos(25 * kDeg), std::sin(25 * kDeg));
  const std::vector<WallSegment> walls{{{-1, -0.1}, {0, -0.1}}, {b, b + out}};
  const auto features = extract_features(scan_of(walls, 0.3, {}, 0.5));
  ASSERT_EQ(features.size(), 2u);
  EXPECT_EQ(features[0].kind, FeatureKind::Wall);
  EXPECT_EQ(features[1].kind, FeatureKind::Wall);
  expect_near(features[0].point, {0, -0.1}, 1e-9);
  const Eigen::Vector2d n(-out.y(), out.x());
  expect_near(features[1].point, b.dot(n) * n, 1e-9);
}

TEST(ScanFeatures, TheEdgeOfAPartialScanIsNoCorner) {
  // The scene of the arriving one-wall corner seen by 80 beams, 230.3 to 309.3 deg: the wall's
  // run stops at the scan's edge, the last reading no jump; nothing is known beyond it.
  const std::vector<WallSegment> walls{{{-1, -0.1}, {0.1, -0.1}}, {{0.1, -0.1}, {0.1, -1}}};
  const RangeScan scan = simulate_segment_scan(walls, {}, 80, 230.3 * kDeg, kDeg, 0.3);
  ASSERT_EQ(returns_of(scan), 80);
  const auto features = extract_features(scan);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features[0].kind, FeatureKind::Wall);
  expect_near(features[0].point, {0, -0.1}, 1e-9);
}

TEST(ScanFeatures, NothingSeenIsNoFeatureAndNoError) {
  EXPECT_TRUE(extract_features(scan_of({}, 0.3)).empty());
  EXPECT_TRUE(extract_features(scan_of({{{-1, -0.5}, {1, -0.5}}}, 0.3)).empty());  // too far
  // Returns too few for a wall (a 2 cm post): no feature either.
  EXPECT_TRUE(extract_features(scan_of({{{0.2, -0.01}, {0.2, 0.01}}}, 0.3)).empty());
}

TEST(ScanFeatures, CornerOf120Degrees) {
  // The wall y = -0.1 into (0.1, -0.1), then a wall turning left by 60 deg.
  const Eigen::Vector2d c(0.1, -0.1), out(0.5, std::sqrt(0.75));
  const std::vector<WallSegment> walls{{{-1, -0.1}, c}, {c, c + out}};
  const auto features = extract_features(scan_of(walls, 0.3));
  ASSERT_EQ(features.size(), 1u);
  const ScanFeature& f = features[0];
  EXPECT_EQ(f.kind, FeatureKind::ConcaveCorner);
  expect_near(f.point, c, 0.002);
  EXPECT_NEAR(f.free_angle, 2 * kPi / 3, 1e-6);
  expect_near(f.wall2, out, 1e-9);
  // Eqs. 3.15-3.16's sum of the offsets is no corner of walls that are not perpendicular;
  // cartesian_offsets still finds it.
  const FeatureOffsets o = feature_offsets(f);
  EXPECT_GT((o.offset1 + o.offset2 - c).norm(), 0.05);
  expect_near(cartesian_offsets(f, {1, 0}, out), c, 0.002);
}

TEST(ScanFeatures, ClosedRoomGivesItsFourCornersNearestFirst) {
  // A room x in [-0.15, 0.25], y in [-0.2, 0.3] seen whole: one run round the whole turn.
  const std::vector<Eigen::Vector2d> v{{-0.15, -0.2}, {0.25, -0.2}, {0.25, 0.3}, {-0.15, 0.3}};
  const std::vector<WallSegment> walls{{v[0], v[1]}, {v[1], v[2]}, {v[2], v[3]}, {v[3], v[0]}};
  const RangeScan scan = scan_of(walls, 0.8);
  ASSERT_EQ(returns_of(scan), 360);
  const auto features = extract_features(scan);
  ASSERT_EQ(features.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(features[i].kind, FeatureKind::ConcaveCorner);
    EXPECT_NEAR(features[i].free_angle, kPi / 2, 1e-6);
  }
  expect_near(features[0].point, v[0], 0.002);  // 0.25 m
  expect_near(features[1].point, v[1], 0.002);  // 0.32 m
  expect_near(features[2].point, v[3], 0.002);  // 0.34 m
  expect_near(features[3].point, v[2], 0.002);  // 0.39 m
}

/// A scene seen from the origin and what it shows: the feature's point and the directions of
/// its walls (scan order), in the frame of the robot.
struct OffsetScene {
  const char* name;
  std::vector<WallSegment> walls;
  FeatureKind kind;
  Eigen::Vector2d point, wall1, wall2;
  bool arrives = false;
  double first_deg = 0.0;
};

std::vector<OffsetScene> offset_scenes() {
  const Eigen::Vector2d c120(0.1, -0.1), out120(0.5, std::sqrt(0.75));
  return {
      {"concave 90", kConcave, FeatureKind::ConcaveCorner, {0.15, -0.1}, {1, 0}, {0, 1}},
      {"concave 120",
       {{{-1, -0.1}, c120}, {c120, c120 + out120}},
       FeatureKind::ConcaveCorner,
       c120,
       {1, 0},
       out120},
      {"convex",
       {{{1, 0.1}, {0.1, 0.1}}, {{0.1, 0.1}, {0.1, 1}}},
       FeatureKind::ConvexCorner,
       {0.1, 0.1},
       {-1, 0},
       {0, 1}},
      {"one wall arriving",
       {{{-1, -0.1}, {0.1, -0.1}}, {{0.1, -0.1}, {0.1, -1}}},
       FeatureKind::ConvexCornerOneWall,
       {0.1, -0.1},
       {1, 0},
       {0, 0},
       true,
       0.3},
      {"one wall leaving",
       {{{-0.1, -0.1}, {1, -0.1}}, {{-0.1, -0.1}, {-0.1, -1}}},
       FeatureKind::ConvexCornerOneWall,
       {-0.1, -0.1},
       {1, 0},
       {0, 0},
       false,
       0.3},
      {"wall", {{{-1, -0.1}, {1, -0.1}}}, FeatureKind::Wall, {0, -0.1}, {1, 0}, {0, 0}},
  };
}

// The robot at (1.3, -0.7) facing 0.9 rad: the map holds the scene placed by that pose.
const Pose2 kRobot{1.3, -0.7, 0.9};

TEST(FeatureOffsets, CartesianOffsetsOfExactFeaturesReachTheMapPoint) {
  for (const OffsetScene& s : offset_scenes()) {
    SCOPED_TRACE(s.name);
    ScanFeature f;
    f.kind = s.kind;
    f.point = s.point;
    f.wall1 = s.wall1;
    f.wall2 = s.wall2;
    f.seen_wall_arrives = s.arrives;
    const Eigen::Vector2d map_point =
        Eigen::Vector2d(kRobot.x, kRobot.y) + rotated(s.point, kRobot.theta);
    const Eigen::Vector2d env1 = rotated(s.wall1, kRobot.theta);
    const Eigen::Vector2d env2 = rotated(s.wall2, kRobot.theta);
    expect_near(cartesian_offsets(f, env1, env2), map_point - Eigen::Vector2d(kRobot.x, kRobot.y),
                1e-12);
  }
}

TEST(FeatureOffsets, CartesianOffsetsOfExtractedFeaturesReachTheMapPoint) {
  for (const OffsetScene& s : offset_scenes()) {
    SCOPED_TRACE(s.name);
    const RangeScan scan = scan_of(placed(s.walls, kRobot), 0.3, kRobot, s.first_deg);
    const auto features = extract_features(scan);
    ASSERT_EQ(features.size(), 1u);
    const ScanFeature& f = features[0];
    ASSERT_EQ(f.kind, s.kind);
    EXPECT_EQ(f.seen_wall_arrives, s.arrives);
    // The map walls' directions, and the map-frame vector from the robot to the map's corner
    // (or to the foot of the perpendicular on the wall).
    const Eigen::Vector2d env1 = rotated(s.wall1, kRobot.theta);
    const Eigen::Vector2d env2 = rotated(s.wall2, kRobot.theta);
    const Eigen::Vector2d want = rotated(s.point, kRobot.theta);
    // A one-wall corner's point is the wall's last return, up to a beam step short of it.
    const double tol = s.kind == FeatureKind::ConvexCornerOneWall ? 0.003 : 0.002;
    expect_near(cartesian_offsets(f, env1, env2), want, tol);
  }
}

TEST(FeatureOffsets, OffsetsFollowTheThesisEquations) {
  ScanFeature f;  // a corner (0.2, 0.1) whose walls run (0.6, 0.8) then (-0.8, 0.6)
  f.kind = FeatureKind::ConvexCorner;
  f.point = {0.2, 0.1};
  f.wall1 = {0.6, 0.8};
  f.wall2 = {-0.8, 0.6};
  const FeatureOffsets o = feature_offsets(f);
  const Eigen::Vector2d n1(-0.8, 0.6), n2(-0.6, -0.8);  // [0 0 1] x wall (eqs. 3.6-3.7)
  expect_near(o.offset1, f.point.dot(n1) * n1, 1e-15);  // eq. 3.8
  expect_near(o.offset2, f.point.dot(n2) * n2, 1e-15);  // eq. 3.9
  // Perpendicular walls: the offsets add up to the corner (eqs. 3.15-3.16 with T = identity).
  expect_near(cartesian_offsets(f, f.wall1, f.wall2), o.offset1 + o.offset2, 1e-15);
  expect_near(o.offset1 + o.offset2, f.point, 1e-15);
}

TEST(FeatureOffsets, RefusesWallsThatAreNoDirections) {
  ScanFeature f;
  f.kind = FeatureKind::ConcaveCorner;
  f.point = {0.1, 0.1};
  f.wall1 = {1, 0};
  test::expect_error([&] { feature_offsets(f); }, {"feature_offsets", "wall2"});
  f.wall2 = {0, 1};
  test::expect_error(
      [&] {
        cartesian_offsets(f, {1, 0}, {2, 0});
      },
      {"cartesian_offsets", "map walls", "parallel"});
  test::expect_error([&] { cartesian_offsets(f, {0, 0}, {0, 1}); }, {"env_wall1"});
  f.wall2 = {-1, 0};
  test::expect_error([&] { cartesian_offsets(f, {1, 0}, {0, 1}); }, {"feature's walls"});
}

TEST(ScanFeatures, KindNames) {
  EXPECT_EQ(to_string(FeatureKind::ConcaveCorner), "concave corner");
  EXPECT_EQ(to_string(FeatureKind::ConvexCorner), "convex corner");
  EXPECT_EQ(to_string(FeatureKind::ConvexCornerOneWall), "convex corner (one wall)");
  EXPECT_EQ(to_string(FeatureKind::Wall), "wall");
}

TEST(ScanFeatures, RefusesBadOptionsAndScans) {
  const RangeScan scan = scan_of(kConcave, 0.3);
  auto with = [&](auto change) {
    FeatureOptions o;
    change(o);
    return [scan, o] { extract_features(scan, o); };
  };
  test::expect_error(with([](FeatureOptions& o) { o.split_m = 0.0; }), {"FeatureOptions: split_m"});
  test::expect_error(
      with([](FeatureOptions& o) { o.gap_m = std::numeric_limits<double>::quiet_NaN(); }),
      {"FeatureOptions: gap_m"});
  test::expect_error(with([](FeatureOptions& o) { o.min_wall_points = 1; }),
                     {"FeatureOptions: min_wall_points"});
  test::expect_error(with([](FeatureOptions& o) { o.min_wall_m = -1.0; }),
                     {"FeatureOptions: min_wall_m"});
  test::expect_error(with([](FeatureOptions& o) { o.min_turn = 4.0; }),
                     {"FeatureOptions: min_turn"});
  test::expect_error(with([](FeatureOptions& o) { o.saturation_margin_m = -0.1; }),
                     {"FeatureOptions: saturation_margin_m"});
  RangeScan bad = scan;
  bad.ranges[7] = std::numeric_limits<double>::quiet_NaN();
  test::expect_error([&] { extract_features(bad); }, {"beam 7", "NaN"});
  RangeScan unseen = scan_of({}, 0.3);  // no return, but a broken angle
  unseen.angles[3] = std::numeric_limits<double>::infinity();
  test::expect_error([&] { extract_features(unseen); }, {"beam 3", "not finite"});
  unseen.angles.pop_back();
  test::expect_error([&] { extract_features(unseen); }, {"angles", "ranges"});
}

}  // namespace
}  // namespace gridloc
