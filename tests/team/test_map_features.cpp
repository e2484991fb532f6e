// Tests of engine/src/team/map_features.cpp: polygon maps' walls and corners exactly (a
// square, a T, a square around an obstacle, straight and slightly bent vertices), occupancy
// maps' traced and simplified outline against the polygons they were rasterized from, the
// grid's frame, and the errors.
#include "gridloc/engine/team/map_features.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Vector2d left_normal(const MapWall& wall) {
  const Eigen::Vector2d d = (wall.b - wall.a).normalized();
  return {-d.y(), d.x()};
}

/// The T: a 1 m wide stem x in [1, 2], y in [0, 2], under a 3 x 1 m bar; convex at (2, 2)
/// and (1, 2), concave elsewhere.
PolygonMap t_map() {
  return make_polygon_map({{1, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 3}, {0, 3}, {0, 2}, {1, 2}}, {});
}

/// A 6 x 6 m room around a 2 x 2 m obstacle.
PolygonMap room_with_obstacle() {
  return make_polygon_map({{0, 0}, {6, 0}, {6, 6}, {0, 6}}, {{{2, 2}, {4, 2}, {4, 4}, {2, 4}}});
}

TEST(PolygonFeatures, SquareHasFourConcaveRightCornersAndCounterClockwiseWalls) {
  // Given clockwise: the map stores the boundary counter-clockwise.
  const PolygonMap map = make_polygon_map({{0, 0}, {0, 4}, {4, 4}, {4, 0}}, {});
  const MapFeatures f = polygon_features(map);
  const auto edges = polygon_edges(map);
  ASSERT_EQ(f.walls.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(f.walls[k].a, edges[k].first);
    EXPECT_EQ(f.walls[k].b, edges[k].second);
    EXPECT_DOUBLE_EQ((f.walls[k].b - f.walls[k].a).norm(), 4.0);
    // Free space on the left: a point just left of the wall's middle lies inside.
    const Eigen::Vector2d mid = 0.5 * (f.walls[k].a + f.walls[k].b);
    EXPECT_TRUE(inside(map.boundary, mid + 0.01 * left_normal(f.walls[k])));
  }
  ASSERT_EQ(f.corners.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const MapCorner& c = f.corners[k];
    EXPECT_EQ(c.point, map.boundary[k]);
    EXPECT_EQ(c.in, (k + 3) % 4);
    EXPECT_EQ(c.out, k);
    EXPECT_EQ(f.walls[c.in].b, c.point);
    EXPECT_EQ(f.walls[c.out].a, c.point);
    EXPECT_NEAR(c.free_angle, kPi / 2, 1e-12);
    EXPECT_FALSE(c.convex());
  }
}

TEST(PolygonFeatures, TShapeHasSixConcaveAndTwoConvexCorners) {
  const PolygonMap map = t_map();
  const MapFeatures f = polygon_features(map);
  ASSERT_EQ(f.walls.size(), 8u);
  ASSERT_EQ(f.corners.size(), 8u);
  int convex = 0;
  for (const MapCorner& c : f.corners) {
    const bool protruding = c.point == Eigen::Vector2d(2, 2) || c.point == Eigen::Vector2d(1, 2);
    EXPECT_EQ(c.convex(), protruding) << c.point.transpose();
    EXPECT_NEAR(c.free_angle, protruding ? 1.5 * kPi : 0.5 * kPi, 1e-12) << c.point.transpose();
    convex += c.convex();
  }
  EXPECT_EQ(convex, 2);
}

TEST(PolygonFeatures, ObstacleVerticesAreConvexAndItsWallsFaceAway) {
  const PolygonMap map = room_with_obstacle();
  const MapFeatures f = polygon_features(map);
  const auto edges = polygon_edges(map);
  ASSERT_EQ(f.walls.size(), 8u);
  ASSERT_EQ(f.corners.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_EQ(f.walls[k].a, edges[k].first);
    EXPECT_EQ(f.walls[k].b, edges[k].second);
  }
  const Eigen::Vector2d centre(3, 3);
  for (std::size_t k = 4; k < 8; ++k) {  // the obstacle's walls: free side away from it
    const Eigen::Vector2d mid = 0.5 * (f.walls[k].a + f.walls[k].b);
    EXPECT_GT(left_normal(f.walls[k]).dot(mid - centre), 0.0) << k;
  }
  for (int k = 0; k < 8; ++k) {
    const MapCorner& c = f.corners[k];
    EXPECT_EQ(c.convex(), k >= 4) << k;
    EXPECT_NEAR(c.free_angle, k >= 4 ? 1.5 * kPi : 0.5 * kPi, 1e-12) << k;
    EXPECT_EQ(c.out, k);
    EXPECT_EQ(c.in, k < 4 ? (k + 3) % 4 : 4 + (k + 3) % 4);
  }
}

TEST(PolygonFeatures, StraightAndSlightlyBentVerticesAreNoCorner) {
  // (2, 0) lies on the bottom wall; (4.1, 1.5) bends the right wall outward, the free space
  // turning left there by 2 atan(0.1 / 1.5), about 7.6 deg.
  const PolygonMap map = make_polygon_map({{0, 0}, {2, 0}, {4, 0}, {4.1, 1.5}, {4, 3}, {0, 3}}, {});
  const MapFeatures f = polygon_features(map);
  EXPECT_EQ(f.walls.size(), 6u);
  ASSERT_EQ(f.corners.size(), 4u);
  for (const MapCorner& c : f.corners) {
    EXPECT_NE(c.point, Eigen::Vector2d(2, 0));
    EXPECT_NE(c.point, Eigen::Vector2d(4.1, 1.5));
  }
  // (2, 0) at index 1 sits between walls 0 and 1, which stay separate walls.
  EXPECT_EQ(f.corners[1].point, Eigen::Vector2d(4, 0));
  EXPECT_EQ(f.corners[1].in, 1);
  // A smaller min_turn makes the bend (turning left: concave) a corner, the straight vertex not.
  MapFeatureOptions options;
  options.min_turn = deg2rad(5.0);
  const MapFeatures bent = polygon_features(map, options);
  ASSERT_EQ(bent.corners.size(), 5u);
  EXPECT_EQ(bent.corners[2].point, Eigen::Vector2d(4.1, 1.5));
  EXPECT_FALSE(bent.corners[2].convex());
  EXPECT_NEAR(bent.corners[2].free_angle, kPi - 2.0 * std::atan2(0.1, 1.5), 1e-12);
}

/// Expects the occupancy features to give the polygon's corners and walls: one corner within
/// 1.5 cells of each vertex, of the same convexity, and one wall per edge, its ends within 2
/// cells of the edge's, running the same way.
void expect_matches_polygon(const MapFeatures& f, const PolygonMap& map, double cell) {
  const MapFeatures truth = polygon_features(map);
  ASSERT_EQ(f.corners.size(), truth.corners.size());
  for (const MapCorner& t : truth.corners) {
    int near = 0;
    for (const MapCorner& c : f.corners) {
      if ((c.point - t.point).norm() > 1.5 * cell) continue;
      ++near;
      EXPECT_EQ(c.convex(), t.convex()) << t.point.transpose();
      EXPECT_NEAR(c.free_angle, t.free_angle, deg2rad(5.0)) << t.point.transpose();
    }
    EXPECT_EQ(near, 1) << t.point.transpose();
  }
  ASSERT_EQ(f.walls.size(), truth.walls.size());
  for (const MapWall& t : truth.walls) {
    int near = 0;
    for (const MapWall& w : f.walls) {
      near += (w.a - t.a).norm() <= 2.0 * cell && (w.b - t.b).norm() <= 2.0 * cell;
    }
    EXPECT_EQ(near, 1) << t.a.transpose() << " -> " << t.b.transpose();
  }
  for (const MapCorner& c : f.corners) {  // a corner joins the walls it names
    EXPECT_EQ(f.walls[c.in].b, c.point);
    EXPECT_EQ(f.walls[c.out].a, c.point);
  }
}

TEST(OccupancyFeatures, RasterizedTGivesItsCornersAndWalls) {
  const PolygonMap map = t_map();
  for (double cell : {0.05, 0.02}) {
    SCOPED_TRACE("cell " + std::to_string(cell));
    expect_matches_polygon(occupancy_features(rasterize_polygon_map(map, cell)), map, cell);
  }
}

TEST(OccupancyFeatures, SlantedWallsAreFittedThroughTheirSteps) {
  // The T and a 0.4 x 0.5 m obstacle in its stem, turned and shifted off the grid's lines, at
  // 0.02 m (a sweep of 129 turns from 0 to 90 deg put every corner within 1.42 cells and
  // every free angle within 3.3 deg; at 0.05 m, 3 of the 129 missed by up to 1.61 cells or
  // had one extra corner).
  for (double deg : {10.0, 27.0, 45.0, 63.0}) {
    SCOPED_TRACE("turned " + std::to_string(deg) + " deg");
    const double c = std::cos(deg2rad(deg)), s = std::sin(deg2rad(deg));
    const auto turn = [&](const Polygon& ring) {
      Polygon out;
      for (const Eigen::Vector2d& v : ring) {
        out.push_back({c * v.x() - s * v.y() + 0.013, s * v.x() + c * v.y() + 0.007});
      }
      return out;
    };
    const PolygonMap map = make_polygon_map(
        turn(t_map().boundary), {turn({{1.3, 0.5}, {1.7, 0.5}, {1.7, 1.0}, {1.3, 1.0}})});
    expect_matches_polygon(occupancy_features(rasterize_polygon_map(map, 0.02)), map, 0.02);
  }
}

TEST(OccupancyFeatures, ObstacleIsTracedClockwiseWithConvexCornersAndSpecksAreIgnored) {
  const PolygonMap map = room_with_obstacle();
  OccupancyMap grid = rasterize_polygon_map(map, 0.05);
  // A free speck in the unknown margin: an L of 7 cells, its arms 4 cells (0.2 m) long.
  for (int k = 0; k < 4; ++k) grid.at(2 + k, 2) = grid.at(2, 2 + k) = CellState::Free;
  expect_matches_polygon(occupancy_features(grid), map, 0.05);
}

TEST(OccupancyFeatures, RoomsTouchingAtACornerAreSeparateSquares) {
  // Two 5 x 5 cell free blocks meeting only at the corner (6, 6) of the cell grid, on a grid
  // turned by 0.3 rad: two squares of four concave corners each, exactly at the cell corners.
  OccupancyMap grid = test::filled_map(12, 12, CellState::Occupied, 0.1);
  for (int i = 1; i <= 5; ++i) {
    for (int j = 1; j <= 5; ++j) grid.at(i, j) = grid.at(i + 5, j + 5) = CellState::Free;
  }
  const auto corner = [&](int x, int y) -> Eigen::Vector2d {
    const Pose2 p = grid.geometry.to_world_frame({0.1 * x, 0.1 * y, 0.0});
    return {p.x, p.y};
  };
  const MapFeatures f = occupancy_features(grid);
  ASSERT_EQ(f.walls.size(), 8u);
  ASSERT_EQ(f.corners.size(), 8u);
  std::vector<Eigen::Vector2d> expected;
  for (int base : {1, 6}) {
    for (const auto& [x, y] : {std::pair{0, 0}, {5, 0}, {5, 5}, {0, 5}}) {
      expected.push_back(corner(base + x, base + y));
    }
  }
  for (const Eigen::Vector2d& e : expected) {
    int near = 0;
    for (const MapCorner& c : f.corners) {
      if ((c.point - e).norm() > 1e-9) continue;
      ++near;
      EXPECT_NEAR(c.free_angle, kPi / 2, 1e-9);
    }
    EXPECT_EQ(near, e == corner(6, 6) ? 2 : 1) << e.transpose();  // once in each square
  }
}

TEST(OccupancyFeatures, FeaturesFollowTheGridIntoTheWorldFrame) {
  const OccupancyMap grid = rasterize_polygon_map(t_map(), 0.05);
  OccupancyMap moved = grid;
  moved.geometry.origin = {1.0, -2.0};
  moved.geometry.yaw = 0.3;
  const auto to_world = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    const Pose2 w = moved.geometry.to_world_frame(
        {p.x() - grid.geometry.origin.x(), p.y() - grid.geometry.origin.y(), 0.0});
    return {w.x, w.y};
  };
  const MapFeatures f = occupancy_features(grid), g = occupancy_features(moved);
  ASSERT_EQ(g.corners.size(), f.corners.size());
  ASSERT_EQ(g.walls.size(), f.walls.size());
  for (std::size_t k = 0; k < f.corners.size(); ++k) {
    EXPECT_LT((g.corners[k].point - to_world(f.corners[k].point)).norm(), 1e-9) << k;
    EXPECT_NEAR(g.corners[k].free_angle, f.corners[k].free_angle, 1e-9) << k;
  }
}

TEST(OccupancyFeatures, MapWithoutFreeCellsIsAnError) {
  for (CellState fill : {CellState::Unknown, CellState::Occupied}) {
    test::expect_error([&] { occupancy_features(test::filled_map(20, 10, fill, 0.05)); },
                       {"occupancy map has no free cells"});
  }
  test::expect_error([] { occupancy_features(OccupancyMap{}); },
                     {"occupancy map has no free cells"});
}

TEST(MapFeatureValidation, ValidateNamesTheField) {
  EXPECT_NO_THROW(validate(MapFeatureOptions{}));
  const auto expect_refused = [](MapFeatureOptions o, const std::string& field) {
    test::expect_error([&] { validate(o); }, {"MapFeatureOptions", field});
    test::expect_error([&] { polygon_features(t_map(), o); }, {field});
    test::expect_error([&] { occupancy_features(test::filled_map(5, 5, CellState::Free, 0.1), o); },
                       {field});
  };
  for (double bad : {0.0, -0.1, kPi, 4.0, std::nan("")}) {
    MapFeatureOptions o;
    o.min_turn = bad;
    expect_refused(o, "min_turn");
  }
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    MapFeatureOptions o;
    o.simplify_m = bad;
    expect_refused(o, "simplify_m");
    o = {};
    o.min_wall_m = bad;
    expect_refused(o, "min_wall_m");
  }
}

}  // namespace
}  // namespace gridloc
