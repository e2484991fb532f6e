// Tests of grids/include/gridloc/grids/planar.hpp against brute force: the 2-D cross product
// is the z of the 3-D one, antisymmetric, and its sign says which way b turns from a; the
// distance to a segment is that of its nearest point; the total-least-squares line leaves
// the least sum of squared orthogonal distances of any line; two lines meet on both.
#include "gridloc/grids/planar.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace gridloc {
namespace {

TEST(Planar, ASegmentIsItsTwoEndsZeroUnlessGiven) {
  const Segment2 unset;
  EXPECT_EQ(unset.a, Eigen::Vector2d::Zero());
  EXPECT_EQ(unset.b, Eigen::Vector2d::Zero());
  const Segment2 wall{{1.0, 2.0}, {3.0, 4.0}};
  EXPECT_EQ(wall.a, Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(wall.b, Eigen::Vector2d(3.0, 4.0));
}

TEST(Planar, CrossIsTheZOfTheThreeDimensionalCrossProduct) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-100.0, 100.0);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector2d a(value(rng), value(rng)), b(value(rng), value(rng));
    const Eigen::Vector3d a3(a.x(), a.y(), 0.0), b3(b.x(), b.y(), 0.0);
    EXPECT_DOUBLE_EQ(cross(a, b), a3.cross(b3).z()) << k;
    EXPECT_EQ(cross(a, b), -cross(b, a)) << k;
    EXPECT_EQ(cross(a, a), 0.0) << k;
  }
}

TEST(Planar, CrossIsPositiveCounterClockwise) {
  const Eigen::Vector2d east(1.0, 0.0), north(0.0, 1.0);
  EXPECT_EQ(cross(east, north), 1.0);
  EXPECT_EQ(cross(north, east), -1.0);
  EXPECT_EQ(cross(Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(3.0, 4.0)), 8.0);  // the area
}

// The distance to a segment against brute force: the nearest of many points along it.
TEST(Planar, DistanceToSegmentIsTheNearestPointOfIt) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector2d p(value(rng), value(rng)), a(value(rng), value(rng));
    const Eigen::Vector2d b = k % 10 == 0 ? a : Eigen::Vector2d(value(rng), value(rng));
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 20000; ++i) {
      nearest = std::min(nearest, (a + (i / 20000.0) * (b - a) - p).norm());
    }
    const double d = distance_to_segment(p, a, b);
    EXPECT_LE(d, nearest + 1e-12) << k;
    EXPECT_NEAR(d, nearest, 2e-3) << k;  // the sampled point is at most half a step off
    EXPECT_DOUBLE_EQ(squared_distance_to_segment(p, a, b), d * d) << k;
  }
  const Eigen::Vector2d a(0.0, 0.0), b(4.0, 0.0);
  EXPECT_EQ(distance_to_segment({2.0, 3.0}, a, b), 3.0);   // above the middle
  EXPECT_EQ(distance_to_segment({-3.0, 4.0}, a, b), 5.0);  // beyond an end
  EXPECT_EQ(distance_to_segment({7.0, 4.0}, a, b), 5.0);
  EXPECT_EQ(distance_to_segment({3.0, 4.0}, a, a), 5.0);  // a point
}

// The distance to the nearest of several segments against brute force: the nearest of many
// points along all of them.
TEST(Planar, DistanceToNearestIsThatOfTheNearestPointOfAnySegment) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  for (int k = 0; k < 200; ++k) {
    std::vector<Segment2> segments(1 + k % 5);
    for (Segment2& s : segments) s = {{value(rng), value(rng)}, {value(rng), value(rng)}};
    const Eigen::Vector2d p(value(rng), value(rng));
    double sampled = std::numeric_limits<double>::infinity();
    for (const Segment2& s : segments) {
      for (int i = 0; i <= 20000; ++i) {
        sampled = std::min(sampled, (s.a + (i / 20000.0) * (s.b - s.a) - p).norm());
      }
    }
    const double d = distance_to_nearest(
        p, segments.size(), [&](std::size_t i) -> const Segment2& { return segments[i]; });
    EXPECT_LE(d, sampled + 1e-12) << k;
    EXPECT_NEAR(d, sampled, 1e-3) << k;  // the sampled point is at most half a step off
  }
}

TEST(Planar, DistanceToNearestTakesSegmentsByIndex) {
  // A 4 x 3 room as vertices and edges by index pairs (as sectors keep them).
  const std::vector<Eigen::Vector2d> corners = {{0.0, 0.0}, {4.0, 0.0}, {4.0, 3.0}, {0.0, 3.0}};
  const std::vector<std::pair<int, int>> edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const auto edge = [&](std::size_t k) {
    return Segment2{corners[edges[k].first], corners[edges[k].second]};
  };
  EXPECT_EQ(distance_to_nearest({1.0, 2.5}, edges.size(), edge), 0.5);  // the top wall
  EXPECT_EQ(distance_to_nearest({3.0, 1.0}, edges.size(), edge), 1.0);  // right and bottom
  EXPECT_EQ(distance_to_nearest({7.0, 7.0}, edges.size(), edge), 5.0);  // outside, a corner
  EXPECT_EQ(distance_to_nearest({7.0, 7.0}, 0, edge), std::numeric_limits<double>::infinity());
}

// The ray distance against an independent solve: each segment's (t, u) from Eigen's QR on
// [direction, a - b] (t, u) = a - origin, the nearest hit ahead on the segment.
TEST(Planar, RayDistanceIsTheNearestSolvedHit) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> value(-10.0, 10.0),
      angle(-std::numbers::pi, std::numbers::pi);
  const RayTolerances tolerances{.parallel = 1e-12, .slack = 0.0, .origin_counts = false};
  int hits = 0;
  for (int k = 0; k < 1000; ++k) {
    std::vector<Segment2> segments(1 + k % 8);
    for (Segment2& s : segments) s = {{value(rng), value(rng)}, {value(rng), value(rng)}};
    const Eigen::Vector2d origin(value(rng), value(rng));
    const double heading = angle(rng);
    const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
    double reference = std::numeric_limits<double>::infinity();
    bool borderline = false;  // a hit too near an end or parallel for the two solves to agree
    for (const Segment2& s : segments) {
      Eigen::Matrix2d system;
      system << direction, s.a - s.b;
      if (std::abs(cross(direction, (s.b - s.a).normalized())) < 1e-3) borderline = true;
      const Eigen::Vector2d tu = system.colPivHouseholderQr().solve(s.a - origin);
      if (std::abs(tu.y()) < 1e-9 || std::abs(tu.y() - 1.0) < 1e-9) borderline = true;
      if (tu.x() > 0.0 && tu.y() >= 0.0 && tu.y() <= 1.0) reference = std::min(reference, tu.x());
    }
    if (borderline) continue;
    const double t = ray_distance(origin, direction, segments, tolerances);
    if (std::isinf(reference)) {
      EXPECT_TRUE(std::isinf(t)) << k;
    } else {
      ++hits;
      EXPECT_NEAR(t, reference, 1e-9) << k;
      EXPECT_NEAR(
          distance_to_nearest(origin + t * direction, segments.size(),
                              [&](std::size_t i) -> const Segment2& { return segments[i]; }),
          0.0, 1e-9)
          << k;
    }
  }
  EXPECT_GT(hits, 300);  // both outcomes were tried
}

TEST(Planar, RayDistanceKeepsTheCallersTolerances) {
  const std::vector<Segment2> room = {{{-2.0, -1.0}, {2.0, -1.0}},
                                      {{2.0, -1.0}, {2.0, 1.0}},
                                      {{2.0, 1.0}, {-2.0, 1.0}},
                                      {{-2.0, 1.0}, {-2.0, -1.0}}};
  const RayTolerances exact{.parallel = 1e-12, .slack = 0.0, .origin_counts = false};
  const Eigen::Vector2d centre(0.0, 0.0);
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, room, exact), 2.0);
  EXPECT_EQ(ray_distance(centre, {0.0, -1.0}, room, exact), 1.0);
  EXPECT_EQ(ray_distance(centre, {2.0, 0.0}, room, exact), 1.0);  // in lengths of direction
  EXPECT_EQ(ray_distance(centre, {2.0, 1.0}, room, exact), 1.0);  // a corner: both walls' end
  EXPECT_EQ(ray_distance({3.0, 0.0}, {1.0, 0.0}, room, exact),
            std::numeric_limits<double>::infinity());  // every wall behind

  // Slack: a wall ending 1e-13 short of the ray is met only with slack.
  const std::vector<Segment2> short_wall = {{{1.0, 1e-13}, {1.0, 1.0}}};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, short_wall, exact),
            std::numeric_limits<double>::infinity());
  const RayTolerances slack{.parallel = 1e-12, .slack = 1e-12, .origin_counts = false};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, short_wall, slack), 1.0);

  // Parallel: a wall along the ray is never met; one at a slope of 5e-14 only below the
  // caller's parallel threshold.
  const std::vector<Segment2> along = {{{1.0, 0.0}, {3.0, 0.0}}};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, along, exact),
            std::numeric_limits<double>::infinity());
  const std::vector<Segment2> sloped = {{{1.0, -5e-14}, {3.0, 5e-14}}};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, sloped, exact),
            std::numeric_limits<double>::infinity());
  const RayTolerances fine{.parallel = 1e-15, .slack = 0.0, .origin_counts = false};
  EXPECT_DOUBLE_EQ(ray_distance(centre, {1.0, 0.0}, sloped, fine), 2.0);

  // The origin: a wall through it is met at t = 0 only when the caller counts it.
  const std::vector<Segment2> through = {{{0.0, -1.0}, {0.0, 1.0}}};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, through, exact),
            std::numeric_limits<double>::infinity());
  const RayTolerances closed{.parallel = 1e-12, .slack = 0.0, .origin_counts = true};
  EXPECT_EQ(ray_distance(centre, {1.0, 0.0}, through, closed), 0.0);
}

TEST(Planar, TwoLinesMeetWhereEachPassesThrough) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector2d p(value(rng), value(rng)), u(value(rng), value(rng));
    const Eigen::Vector2d q(value(rng), value(rng)), v(value(rng), value(rng));
    if (std::abs(cross(u.normalized(), v.normalized())) < 0.05) continue;  // near parallel
    const Eigen::Vector2d meet = line_intersection(p, u, q, v);
    // On both lines: no distance across either.
    EXPECT_NEAR(cross(u.normalized(), meet - p), 0.0, 1e-9) << k;
    EXPECT_NEAR(cross(v.normalized(), meet - q), 0.0, 1e-9) << k;
  }
  const Eigen::Vector2d meet = line_intersection({0.0, 1.0}, {1.0, 0.0}, {3.0, -2.0}, {0.0, 2.0});
  EXPECT_EQ(meet, Eigen::Vector2d(3.0, 1.0));
}

/// The sum of the squared distances of `points` from the line through `centre` along the
/// unit `direction`.
double orthogonal_squares(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& centre,
                          const Eigen::Vector2d& direction) {
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double off = cross(direction, p - centre);
    sum += off * off;
  }
  return sum;
}

TEST(Planar, TheTotalLeastSquaresLineLeavesTheLeastOrthogonalSquares) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> value(-5.0, 5.0), angle(0.0, std::numbers::pi);
  std::normal_distribution<double> noise(0.0, 0.2);
  for (int k = 0; k < 200; ++k) {
    const double heading = angle(rng);
    const Eigen::Vector2d along(std::cos(heading), std::sin(heading)), base(value(rng), value(rng));
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < 3 + k % 20; ++i) {
      points.push_back(base + value(rng) * along +
                       noise(rng) * Eigen::Vector2d(-along.y(), along.x()));
    }
    const FittedLine line =
        total_least_squares_line(points.size(), [&](std::size_t i) { return points[i]; });
    EXPECT_NEAR(line.direction.norm(), 1.0, 1e-12) << k;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : points) mean += p;
    EXPECT_LE((line.centroid - mean / static_cast<double>(points.size())).norm(), 1e-12) << k;
    const double fitted = orthogonal_squares(points, line.centroid, line.direction);
    for (int a = 0; a < 3600; ++a) {  // any other direction through the centroid, 0.05 deg apart
      const double theta = a * std::numbers::pi / 3600.0;
      const Eigen::Vector2d other(std::cos(theta), std::sin(theta));
      EXPECT_LE(fitted, orthogonal_squares(points, line.centroid, other) + 1e-9) << k;
    }
  }
  const std::vector<Eigen::Vector2d> wall = {{2.0, -1.0}, {2.0, 0.5}, {2.0, 3.0}};  // vertical
  const FittedLine line = total_least_squares_line(3, [&](std::size_t i) { return wall[i]; });
  EXPECT_NEAR(std::abs(line.direction.y()), 1.0, 1e-12);
  EXPECT_NEAR(line.centroid.x(), 2.0, 1e-12);
  EXPECT_NEAR(line.centroid.y(), 2.5 / 3.0, 1e-12);
}

}  // namespace
}  // namespace gridloc
