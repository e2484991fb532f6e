// Range-limited views (seed 002 §III-B): hand-made rooms and brute-force ray casting.
#include "gridloc/engine/disambiguation/range_view.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "disambiguation/view_cases.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

using test::rectangle;
using test::reversed;
constexpr double kPi = std::numbers::pi;

bool has_piece(const RangeView& view, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
               bool a_vertex, bool b_vertex) {
  for (const ViewPiece& piece : view.pieces) {
    if ((piece.segment.a - a).norm() < 1e-9 && (piece.segment.b - b).norm() < 1e-9 &&
        piece.a_is_vertex == a_vertex && piece.b_is_vertex == b_vertex) {
      return true;
    }
  }
  return false;
}

TEST(RangeView, SquareFromItsCentreSeesFourWallsAndFourCorners) {
  const Area square{rectangle(-1, -1, 1, 1), {}};
  // Heading pi/4: the viewer's -x axis points at a corner, so each wall is one piece.
  const RangeView turned = range_view(square, {0, 0}, kPi / 4, kUnlimitedRange);
  ASSERT_EQ(turned.pieces.size(), 4u);
  EXPECT_EQ(visible_vertex_count(turned), 4);
  for (const ViewPiece& piece : turned.pieces) {
    EXPECT_TRUE(piece.a_is_vertex && piece.b_is_vertex);
    EXPECT_NEAR((piece.segment.b - piece.segment.a).norm(), 2.0, 1e-12);
  }
  // Heading 0: the left wall is split where it crosses the -x axis, the first piece from it.
  const RangeView view = range_view(square, {0, 0}, 0.0, kUnlimitedRange);
  ASSERT_EQ(view.pieces.size(), 5u);
  EXPECT_EQ(visible_vertex_count(view), 4);
  EXPECT_TRUE(has_piece(view, {-1, 0}, {-1, -1}, false, true));
  EXPECT_TRUE(has_piece(view, {1, -1}, {1, 1}, true, true));
  EXPECT_TRUE(has_piece(view, {-1, 1}, {-1, 0}, true, false));
  EXPECT_NEAR(view.pieces.front().segment.a.y(), 0.0, 1e-12);
}

TEST(RangeView, ShortRangeSeesNothingAndAMiddleRangeCutsEveryWall) {
  const Area square{rectangle(-1, -1, 1, 1), {}};
  EXPECT_TRUE(range_view(square, {0, 0}, 0.3, 0.9).pieces.empty());
  const RangeView view = range_view(square, {0, 0}, 0.0, 1.25);  // sees |y| <= 0.75 per wall
  ASSERT_EQ(view.pieces.size(), 5u);
  EXPECT_EQ(visible_vertex_count(view), 0);
  EXPECT_TRUE(has_piece(view, {1, -0.75}, {1, 0.75}, false, false));
  EXPECT_TRUE(has_piece(view, {0.75, 1}, {-0.75, 1}, false, false));
  EXPECT_TRUE(has_piece(view, {-1, 0}, {-1, -0.75}, false, false));
  // Heading pi/2: the robot's x axis is the world's y axis.
  const RangeView turned = range_view(square, {0, 0}, kPi / 2, 1.25);
  EXPECT_TRUE(has_piece(turned, {1, -0.75}, {1, 0.75}, false, false));  // the top wall
}

TEST(RangeView, TheReflexCornerOfAnLShapedRoomHidesPartOfTheTopWall) {
  const Area room{{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {}};
  const Eigen::Vector2d viewpoint(1.5, 0.25);
  const RangeView view = range_view(room, viewpoint, 0.0, kUnlimitedRange);
  auto local = [&](double x, double y) -> Eigen::Vector2d {
    return Eigen::Vector2d(x, y) - viewpoint;
  };
  EXPECT_TRUE(has_piece(view, local(2, 1), local(1, 1), true, true));  // the reflex corner
  // The ray through (1, 1) meets the top wall at x = 1/3; (1, 2) is hidden.
  EXPECT_TRUE(has_piece(view, local(1.0 / 3.0, 2), local(0, 2), false, true));
  EXPECT_EQ(visible_vertex_count(view), 5);
  for (const ViewPiece& piece : view.pieces) {
    EXPECT_GT((piece.segment.a - local(1, 2)).norm(), 1e-6);
    EXPECT_GT((piece.segment.b - local(1, 2)).norm(), 1e-6);
  }
}

TEST(RangeView, ASquareHoleHidesTheMiddleOfTheFarWall) {
  const Area room{rectangle(-2, -2, 2, 2), {reversed(rectangle(-0.5, -0.5, 0.5, 0.5))}};
  const Eigen::Vector2d viewpoint(-1.5, 0);
  const RangeView view = range_view(room, viewpoint, 0.0, kUnlimitedRange);
  auto local = [&](double x, double y) -> Eigen::Vector2d {
    return Eigen::Vector2d(x, y) - viewpoint;
  };
  EXPECT_TRUE(has_piece(view, local(-0.5, -0.5), local(-0.5, 0.5), true, true));
  EXPECT_TRUE(has_piece(view, local(2, -2), local(2, -1.75), true, false));
  EXPECT_TRUE(has_piece(view, local(2, 1.75), local(2, 2), false, true));
  EXPECT_EQ(visible_vertex_count(view), 6);  // the room's 4 corners, the hole's near 2
}

TEST(RangeView, TranslatedCopiesLookTheSameAndAMovedWallDoesNot) {
  const Area room{{{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 2}, {0, 2}},
                  {reversed(rectangle(0.5, 0.5, 1, 1.2))}};
  const Eigen::Vector2d shift(17.25, -3.5);
  Area copy = room;
  for (Eigen::Vector2d& p : copy.outer) p += shift;
  for (Eigen::Vector2d& p : copy.holes[0]) p += shift;
  const Eigen::Vector2d viewpoint(1.7, 0.4);
  for (const double range : {kUnlimitedRange, 1.0, 2.0}) {
    const RangeView original = range_view(room, viewpoint, 0.3, range);
    EXPECT_TRUE(same_view(original, range_view(copy, viewpoint + shift, 0.3, range)));
    Area moved = copy;
    moved.outer[1].x() += 0.1, moved.outer[2].x() += 0.1;  // the right wall
    // The right wall is 1.3 from the viewpoint: beyond a range of 1 it moves unseen.
    EXPECT_EQ(same_view(original, range_view(moved, viewpoint + shift, 0.3, range)), range < 1.3);
  }
}

TEST(RangeView, AViewpointOnAWallOrACornerDoesNotBreakIt) {
  const Area square{rectangle(-1, -1, 1, 1), {}};
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0, -1), Eigen::Vector2d(1, 1)}) {
    for (const double range : {kUnlimitedRange, 0.5}) {
      const RangeView view = range_view(square, p, 0.0, range);
      for (const ViewPiece& piece : view.pieces) {
        EXPECT_TRUE(piece.segment.a.allFinite() && piece.segment.b.allFinite());
        EXPECT_LE(piece.segment.a.norm(), range + 1e-9);
      }
      EXPECT_GE(visibility_polygon(square, p, range).size(), 1u);
    }
  }
  // From the middle of the bottom wall: the three other walls, nothing outside the room.
  const RangeView view = range_view(square, {0, -1}, 0.0, kUnlimitedRange);
  EXPECT_EQ(visible_vertex_count(view), 4);
}

TEST(RangeView, BadInputThrows) {
  const Area square{rectangle(-1, -1, 1, 1), {}};
  EXPECT_THROW(range_view(square, {0, 0}, 0.0, 0.0), Error);
  EXPECT_THROW(range_view(square, {0, 0}, 0.0, -1.0), Error);
  EXPECT_THROW(range_view(square, {0, 0}, 0.0, std::nan("")), Error);
  EXPECT_THROW(range_view(square, {std::nan(""), 0}, 0.0, 1.0), Error);
  EXPECT_THROW(range_view(Area{{{0, 0}, {1, 0}}, {}}, {0, 0}, 0.0, 1.0), Error);
  EXPECT_THROW(visibility_polygon(square, {0, 0}, 1.0, 2), Error);
}

/// The world direction of viewer-frame angle `angle` for a robot heading `heading`.
Eigen::Vector2d direction(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

/// Brute force (seed 002 §III-B): along random rays, the nearest wall lies on a piece iff it
/// is within range, no piece lies nearer on the ray; every piece's midpoint is seen.
void expect_matches_ray_casting(const Area& area, const Eigen::Vector2d& viewpoint, double heading,
                                double range, std::mt19937& rng) {
  const RangeView view = range_view(area, viewpoint, heading, range);
  for (int ray = 0; ray < 2000; ++ray) {
    const double angle = test::uniform_real(rng, -kPi, kPi);
    const double wall = test::cast_ray(area, viewpoint, direction(angle + heading));
    const Eigen::Vector2d hit = wall * direction(angle);  // viewer frame
    double on_piece = std::numeric_limits<double>::infinity();
    for (const ViewPiece& piece : view.pieces) {
      on_piece = std::min(on_piece, test::ray_to_segment({0, 0}, direction(angle), piece.segment.a,
                                                         piece.segment.b));
    }
    if (wall <= range) {
      ASSERT_NEAR(on_piece, wall, 1e-7) << "ray " << angle << " hit " << hit.transpose();
    } else {
      ASSERT_TRUE(std::isinf(on_piece)) << "ray " << angle << " piece at " << on_piece;
    }
  }
  double previous = -kPi;
  for (const ViewPiece& piece : view.pieces) {
    const Eigen::Vector2d middle = 0.5 * (piece.segment.a + piece.segment.b);
    const double distance = middle.norm();
    ASSERT_LE(distance, range + 1e-9);
    const double seen =
        test::cast_ray(area, viewpoint, direction(std::atan2(middle.y(), middle.x()) + heading));
    ASSERT_GE(seen, distance - 1e-9);
    double angle_a = std::atan2(piece.segment.a.y(), piece.segment.a.x());
    if (angle_a >= kPi - 1e-12) angle_a = -kPi;
    ASSERT_GE(angle_a, previous - 1e-9);
    ASSERT_GT(test::cross2(piece.segment.a, piece.segment.b), 0.0);  // a before b ccw
    previous = angle_a;
  }
}

TEST(RangeView, MatchesRayCastingInRandomStarRoomsWithHoles) {
  std::mt19937 rng(2002);
  for (int room = 0; room < 12; ++room) {
    const Area area = test::random_star_room(rng);
    for (int view = 0; view < 3; ++view) {
      const double range = view == 0 ? kUnlimitedRange : test::uniform_real(rng, 0.3, 5.0);
      expect_matches_ray_casting(area, test::random_inside(rng, area),
                                 test::uniform_real(rng, -kPi, kPi), range, rng);
    }
  }
}

TEST(RangeView, MatchesRayCastingInRandomRectilinearRooms) {
  std::mt19937 rng(4002);
  for (int room = 0; room < 8; ++room) {
    const Area area = test::random_rectilinear_room(rng, room < 4 ? 12 : 40);
    for (int view = 0; view < 3; ++view) {
      const double range = view == 0 ? kUnlimitedRange : test::uniform_real(rng, 0.5, 6.0);
      // Headings of quarter turns put the seam along walls and through vertices.
      const double heading = room % 2 == 0 ? kPi / 2 * test::uniform_int(rng, -2, 1)
                                           : test::uniform_real(rng, -kPi, kPi);
      // Half-integer viewpoints line up with the grid of vertices (collinear events).
      Eigen::Vector2d viewpoint = test::random_inside(rng, area, 0.05);
      if (view == 2) viewpoint = (2.0 * viewpoint).array().round() / 2.0 + 0.25;
      if (!test::strictly_inside(area, viewpoint)) continue;
      expect_matches_ray_casting(area, viewpoint, heading, range, rng);
    }
  }
}

TEST(RangeView, CongruentRandomViewsAreTheSame) {
  std::mt19937 rng(6002);
  for (int room = 0; room < 20; ++room) {
    const Area area = test::random_star_room(rng);
    const Eigen::Vector2d shift(test::uniform_real(rng, -50, 50), test::uniform_real(rng, -50, 50));
    Area copy = area;
    for (Eigen::Vector2d& p : copy.outer) p += shift;
    for (Polygon& hole : copy.holes) {
      for (Eigen::Vector2d& p : hole) p += shift;
    }
    const Eigen::Vector2d viewpoint = test::random_inside(rng, area);
    const double range = room % 2 ? kUnlimitedRange : test::uniform_real(rng, 0.5, 5.0);
    const double heading = test::uniform_real(rng, -kPi, kPi);
    EXPECT_TRUE(same_view(range_view(area, viewpoint, heading, range),
                          range_view(copy, viewpoint + shift, heading, range)));
  }
}

/// The seen area by brute force: dense rays, a triangle fan of min(wall, range).
double fan_area(const Area& area, const Eigen::Vector2d& viewpoint, double range) {
  const int rays = 20000;
  double total = 0.0;
  for (int k = 0; k < rays; ++k) {
    const double r =
        std::min(range, test::cast_ray(area, viewpoint, direction(2 * kPi * (k + 0.5) / rays)));
    total += 0.5 * r * r * 2 * kPi / rays;
  }
  return total;
}

TEST(VisibilityPolygon, AreaMatchesDenseRays) {
  std::mt19937 rng(8002);
  for (int room = 0; room < 10; ++room) {
    const Area area =
        room % 2 ? test::random_star_room(rng) : test::random_rectilinear_room(rng, 10);
    const Eigen::Vector2d viewpoint = test::random_inside(rng, area, 0.01);
    for (const double range : {kUnlimitedRange, 1.0, 2.5}) {
      const Polygon polygon = visibility_polygon(area, viewpoint, range);
      const double size = 0.5 * signed_area2(polygon);
      const double expected = fan_area(area, viewpoint, range);
      EXPECT_NEAR(size, expected, 0.01 * expected) << "room " << room << " range " << range;
    }
  }
}

// useful_region's samples stand 1e-7 from a wall: the many slivers of intervals toward that
// wall must stay on it (they once produced points at infinity).
TEST(VisibilityPolygon, ViewpointsJustOffAWallStayFinite) {
  std::mt19937 rng(7);
  for (const int columns : {12, 40}) {
    const Area area = test::random_rectilinear_room(rng, columns);
    int checked = 0;
    for (const PlanarSegment& edge : area_edges(area)) {
      const Eigen::Vector2d along = (edge.b - edge.a).normalized();
      for (int k = 0; k < 16; ++k) {  // as useful_region spreads its samples
        const Eigen::Vector2d viewpoint = edge.a + (k + 0.5) / 16 * (edge.b - edge.a) +
                                          1e-7 * Eigen::Vector2d(-along.y(), along.x());
        const Polygon polygon = visibility_polygon(area, viewpoint, kUnlimitedRange);
        for (const Eigen::Vector2d& p : polygon) ASSERT_TRUE(p.allFinite()) << viewpoint;
        const double size = 0.5 * signed_area2(polygon);
        ASSERT_GT(size, 0.0);
        ASSERT_LE(size, area_size(area) + 1e-9);
        if (k == 7 && ++checked % 20 == 0) {
          EXPECT_NEAR(size, fan_area(area, viewpoint, kUnlimitedRange), 0.01 * size);
        }
      }
    }
  }
}

TEST(VisibilityPolygon, SquareCentreWithinRangeIsAPolygonOfTheCircle) {
  const Area square{rectangle(-5, -5, 5, 5), {}};
  const Polygon disk = visibility_polygon(square, {0.5, 0.5}, 1.0, 64);
  EXPECT_EQ(disk.size(), 64u);
  EXPECT_NEAR(0.5 * signed_area2(disk), 32 * std::sin(2 * kPi / 64), 1e-9);
  const Polygon whole = visibility_polygon(square, {0.5, 0.5}, kUnlimitedRange);
  EXPECT_NEAR(0.5 * signed_area2(whole), 100.0, 1e-9);
}

}  // namespace
}  // namespace gridloc
