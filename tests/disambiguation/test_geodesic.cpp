// Shortest paths inside an area (seed 002's distance_OI): segment_inside by hand cases, the
// geodesic distance by closed-form cases and against a fine-grid Dijkstra on random
// rectilinear rooms.
#include "gridloc/engine/disambiguation/geodesic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>

#include "test_support.hpp"

namespace gridloc {
namespace {

using Vec = Eigen::Vector2d;

Polygon rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

Polygon clockwise(Polygon ring) {
  std::reverse(ring.begin(), ring.end());
  return ring;
}

/// [0,3]x[0,3] with the notch [1,2]x[1,3] cut from the top: reflex corners (1,1) and (2,1).
Area u_room() {
  return Area{{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}, {}};
}

/// [0,4]x[0,4] with the obstacle [1,3]x[1,3].
Area ring_room() {
  return Area{rectangle(0, 0, 4, 4), {clockwise(rectangle(1, 1, 3, 3))}};
}

TEST(SegmentInside, HandCases) {
  const Area u = u_room();
  EXPECT_TRUE(segment_inside(u, {0, 0}, {3, 0}));           // along a wall
  EXPECT_TRUE(segment_inside(u, {1, 1}, {2, 1}));           // along the notch's floor
  EXPECT_TRUE(segment_inside(u, {0, 2}, {2, 0}));           // touching the reflex vertex (1, 1)
  EXPECT_FALSE(segment_inside(u, {0.5, 2.5}, {2.5, 0.5}));  // cuts the notch's corner
  EXPECT_FALSE(segment_inside(u, {0.5, 2.5}, {2.5, 2.5}));  // through the notch (crossing)
  EXPECT_FALSE(segment_inside(u, {1, 3}, {2, 3}));          // across the notch's mouth
  EXPECT_FALSE(segment_inside(u, {0, 3}, {3, 3}));          // out and back through the notch
  EXPECT_FALSE(segment_inside(u, {0.5, 0.5}, {4, 0.5}));    // out through a wall
  EXPECT_TRUE(segment_inside(u, {0.5, 0.5}, {0.5, 0.5}));   // a point inside
  const Area ring = ring_room();
  EXPECT_FALSE(segment_inside(ring, {0.5, 2}, {3.5, 2}));  // crossing the hole
  EXPECT_FALSE(segment_inside(ring, {1, 1}, {3, 3}));      // the hole's diagonal
  EXPECT_TRUE(segment_inside(ring, {1, 1}, {3, 1}));       // along the hole's wall
  EXPECT_TRUE(segment_inside(ring, {0, 2}, {2, 0}));       // touching the hole's corner
  EXPECT_TRUE(segment_inside(ring, {0, 0}, {4, 0}));
}

TEST(Geodesic, UShapedRoomBendsAtTwoReflexCorners) {
  const GeodesicDistance geodesic(u_room(), {0.5, 2.5});
  const double expected = 2.0 * std::sqrt(0.25 + 2.25) + 1.0;  // (1,1) then (2,1)
  EXPECT_NEAR(geodesic.distance_to({2.5, 2.5}), expected, 1e-12);
  const std::vector<Vec> path = geodesic.path_to({2.5, 2.5});
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path[0], Vec(0.5, 2.5));
  EXPECT_EQ(path[1], Vec(1, 1));
  EXPECT_EQ(path[2], Vec(2, 1));
  EXPECT_EQ(path[3], Vec(2.5, 2.5));
  EXPECT_NEAR(geodesic.distance_to({0.5, 0.5}), 2.0, 1e-12);  // in sight
  EXPECT_EQ(geodesic.path_to({0.5, 0.5}).size(), 2u);
  EXPECT_NEAR(geodesic.distance_to({0.5, 2.5}), 0.0, 1e-12);
  EXPECT_NEAR(geodesic.distance_to({2, 3}), std::sqrt(2.5) + 1.0 + 2.0, 1e-12);  // wall tip
}

TEST(Geodesic, AroundAnObstacleBendsAtItsConvexCorners) {
  const GeodesicDistance geodesic(ring_room(), {0.5, 2});
  EXPECT_NEAR(geodesic.distance_to({3.5, 2}), 2.0 * std::sqrt(0.25 + 1.0) + 2.0, 1e-12);
  const std::vector<Vec> path = geodesic.path_to({3.5, 2});
  ASSERT_EQ(path.size(), 4u);
  EXPECT_DOUBLE_EQ(std::abs(path[1].y() - 2.0), 1.0);  // (1, 1) or (1, 3), then x = 3
  EXPECT_EQ(path[2].x(), 3.0);
}

TEST(Geodesic, ARotatedRoomKeepsItsDistances) {
  const Pose2 turn{0.3, -0.7, 0.5};  // rotated coordinates are no longer exact
  auto rotate = [&](const Area& area) { return to_start_frame(turn, area); };
  const std::vector<std::pair<Area, std::vector<Vec>>> cases{
      {u_room(), {Vec(2.5, 2.5), Vec(2, 0.5), Vec(2.9, 2.9), Vec(2, 3)}},
      {ring_room(), {Vec(3.5, 2), Vec(2, 0.5), Vec(3.5, 3.5), Vec(3, 3)}}};
  for (const auto& [room, targets] : cases) {
    const Vec source(0.5, 2.5);
    const GeodesicDistance plain(room, source);
    const GeodesicDistance turned(rotate(room), to_start_frame(turn, source));
    for (const Vec& target : targets) {
      const double expected = plain.distance_to(target);
      ASSERT_LT(expected, 10.0) << target.transpose();
      EXPECT_NEAR(turned.distance_to(to_start_frame(turn, target)), expected, 1e-9)
          << target.transpose();
    }
  }
}

TEST(Geodesic, OutsideTargetsAndSources) {
  const GeodesicDistance geodesic(u_room(), {0.5, 2.5});
  EXPECT_EQ(geodesic.distance_to({1.5, 2}), std::numeric_limits<double>::infinity());  // notch
  EXPECT_TRUE(geodesic.path_to({1.5, 2}).empty());
  EXPECT_EQ(geodesic.distance_to({-1, 0}), std::numeric_limits<double>::infinity());
  test::expect_error(
      [] {
        GeodesicDistance(u_room(), {1.5, 2.0});
      },
      {"GeodesicDistance", "source", "(1.5"});
  test::expect_error([] { GeodesicDistance(Area{}, {0, 0}); }, {"fewer than 3"});
}

// ---- brute force: a fine-grid Dijkstra on rooms whose walls lie on the unit grid ----

constexpr double kStep = 0.05;  ///< the fine grid (20 nodes a unit: walls lie on grid lines)

/// A rectilinear room made of unit columns: column i is [i, i+1] x [low_i, high_i], with
/// neighbours overlapping, and optional rectangular holes; `inside` is its closed membership.
struct GridRoom {
  Area area;
  std::function<bool(const Vec&)> inside;
  double width = 0, height = 0;
};

/// The ring of a column room: bottom chain left to right, top chain right to left.
Polygon column_ring(const std::vector<int>& low, const std::vector<int>& high) {
  Polygon ring;
  auto add = [&](double x, double y) {
    if (ring.empty() || ring.back() != Vec(x, y)) ring.emplace_back(x, y);
  };
  for (std::size_t i = 0; i < low.size(); ++i) add(i, low[i]), add(i + 1.0, low[i]);
  for (std::size_t i = high.size(); i-- > 0;) add(i + 1.0, high[i]), add(i, high[i]);
  return ring;
}

GridRoom random_column_room(std::mt19937& rng, int columns) {
  std::uniform_int_distribution<int> pick(0, 6);
  std::vector<int> low, high;
  while (static_cast<int>(low.size()) < columns) {
    int a = pick(rng), b = pick(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    if (!low.empty() && (a >= high.back() || b <= low.back())) continue;  // must overlap
    low.push_back(a);
    high.push_back(b);
  }
  GridRoom room{Area{column_ring(low, high), {}}, {}, double(columns), 6.0};
  room.inside = [low, high](const Vec& p) {
    for (std::size_t i = 0; i < low.size(); ++i) {
      if (p.x() >= i - 1e-12 && p.x() <= i + 1 + 1e-12 && p.y() >= low[i] - 1e-12 &&
          p.y() <= high[i] + 1e-12) {
        return true;
      }
    }
    return false;
  };
  return room;
}

/// [0,7]x[0,7] with up to three 1x1 or 2x1 obstacles, never touching each other or a wall.
GridRoom random_room_with_holes(std::mt19937& rng) {
  std::uniform_int_distribution<int> corner(0, 2), wide(1, 2);
  std::vector<Eigen::Vector4d> boxes;  // x0 y0 x1 y1
  auto apart = [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
    return a[0] > b[2] || b[0] > a[2] || a[1] > b[3] || b[1] > a[3];
  };
  for (int k = 0; k < 3; ++k) {
    const double x0 = 1 + 2 * corner(rng), y0 = 1 + 2 * corner(rng);
    const Eigen::Vector4d box(x0, y0, x0 + wide(rng), y0 + 1);
    bool clash = false;
    for (const auto& other : boxes) clash = clash || !apart(box, other);
    if (!clash) boxes.push_back(box);
  }
  GridRoom room{Area{rectangle(0, 0, 7, 7), {}}, {}, 7.0, 7.0};
  for (const auto& b : boxes)
    room.area.holes.push_back(clockwise(rectangle(b[0], b[1], b[2], b[3])));
  room.inside = [boxes](const Vec& p) {
    if (p.x() < -1e-12 || p.x() > 7 + 1e-12 || p.y() < -1e-12 || p.y() > 7 + 1e-12) return false;
    for (const auto& b : boxes) {
      if (p.x() > b[0] + 1e-12 && p.x() < b[2] - 1e-12 && p.y() > b[1] + 1e-12 &&
          p.y() < b[3] - 1e-12) {
        return false;
      }
    }
    return true;
  };
  return room;
}

/// Distances over the 8-connected fine grid from `source` (a grid node), stepping only where
/// the step's midpoint is in the room (walls lie on grid lines, so each step's cell is
/// wholly in or out).
std::vector<double> grid_distances(const GridRoom& room, const Vec& source, int& nx, int& ny) {
  nx = static_cast<int>(std::lround(room.width / kStep)) + 1;
  ny = static_cast<int>(std::lround(room.height / kStep)) + 1;
  auto at = [&](int i, int j) { return Vec(i * kStep, j * kStep); };
  std::vector<double> dist(static_cast<std::size_t>(nx) * ny,
                           std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  const int start = static_cast<int>(std::lround(source.y() / kStep)) * nx +
                    static_cast<int>(std::lround(source.x() / kStep));
  dist[start] = 0;
  queue.push({0.0, start});
  while (!queue.empty()) {
    const auto [d, node] = queue.top();
    queue.pop();
    if (d > dist[node]) continue;
    const int i = node % nx, j = node / nx;
    for (int di = -1; di <= 1; ++di) {
      for (int dj = -1; dj <= 1; ++dj) {
        const int a = i + di, b = j + dj;
        if ((di == 0 && dj == 0) || a < 0 || b < 0 || a >= nx || b >= ny) continue;
        if (!room.inside(at(a, b)) || !room.inside(0.5 * (at(i, j) + at(a, b)))) continue;
        const double next = d + kStep * std::hypot(di, dj);
        if (next < dist[b * nx + a]) dist[b * nx + a] = next, queue.push({next, b * nx + a});
      }
    }
  }
  return dist;
}

/// The area's reflex vertices, by hand (turning right with the area on the left).
std::vector<Vec> reflex_vertices(const Area& area) {
  std::vector<Vec> reflex;
  std::vector<Polygon> rings{area.outer};
  rings.insert(rings.end(), area.holes.begin(), area.holes.end());
  for (const Polygon& r : rings) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Vec u = r[i] - r[(i + r.size() - 1) % r.size()], v = r[(i + 1) % r.size()] - r[i];
      if (u.x() * v.y() - u.y() * v.x() < 0) reflex.push_back(r[i]);
    }
  }
  return reflex;
}

/// The exact shortest length by brute force: Dijkstra over every vertex of the area (no
/// pruning), the source and the target, linked where segment_inside holds.
double all_vertices_distance(const Area& area, const Vec& source, const Vec& target) {
  std::vector<Vec> points{source};
  points.insert(points.end(), area.outer.begin(), area.outer.end());
  for (const Polygon& hole : area.holes) points.insert(points.end(), hole.begin(), hole.end());
  points.push_back(target);
  std::vector<double> dist(points.size(), std::numeric_limits<double>::infinity());
  std::vector<bool> done(points.size(), false);
  dist[0] = 0;
  for (std::size_t round = 0; round < points.size(); ++round) {
    std::size_t u = points.size();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!done[i] && dist[i] < std::numeric_limits<double>::infinity() &&
          (u == points.size() || dist[i] < dist[u])) {
        u = i;
      }
    }
    if (u == points.size()) break;
    done[u] = true;
    for (std::size_t v = 0; v < points.size(); ++v) {
      const double next = dist[u] + (points[v] - points[u]).norm();
      if (!done[v] && next < dist[v] && segment_inside(area, points[u], points[v])) dist[v] = next;
    }
  }
  return dist.back();
}

void expect_matches_grid(const GridRoom& room, const Vec& source, std::mt19937& rng) {
  int nx = 0, ny = 0;
  const std::vector<double> grid = grid_distances(room, source, nx, ny);
  const GeodesicDistance geodesic(room.area, source);
  const std::vector<Vec> reflex = reflex_vertices(room.area);
  std::uniform_int_distribution<int> node(0, nx * ny - 1);
  for (int n = 0; n < 200; ++n) {
    const int k = node(rng);
    const Vec target((k % nx) * kStep, (k / nx) * kStep);
    const double exact = geodesic.distance_to(target);
    if (!room.inside(target)) {
      EXPECT_EQ(exact, std::numeric_limits<double>::infinity()) << target.transpose();
      continue;
    }
    EXPECT_LE(exact, grid[k] + 1e-9) << target.transpose();
    EXPECT_GE(exact, grid[k] / 1.09 - 1e-9) << target.transpose();
    if (n % 10 == 0) {
      EXPECT_NEAR(exact, all_vertices_distance(room.area, source, target), 1e-9)
          << target.transpose();
    }
    const std::vector<Vec> path = geodesic.path_to(target);
    ASSERT_GE(path.size(), 2u);
    double length = 0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      length += (path[i + 1] - path[i]).norm();
      EXPECT_TRUE(segment_inside(room.area, path[i], path[i + 1]));
      if (i > 0) {
        EXPECT_NE(std::find(reflex.begin(), reflex.end(), path[i]), reflex.end());
      }
    }
    EXPECT_NEAR(length, exact, 1e-9);
  }
}

TEST(Geodesic, MatchesAFineGridDijkstraOnRandomColumnRooms) {
  std::mt19937 rng(2002);
  for (int trial = 0; trial < 6; ++trial) {
    const GridRoom room = random_column_room(rng, 7);
    const Vec source(0.5, room.area.outer.front().y() + 0.25);  // in column 0
    expect_matches_grid(room, source, rng);
  }
}

TEST(Geodesic, MatchesAFineGridDijkstraAroundRandomObstacles) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 4; ++trial) {
    expect_matches_grid(random_room_with_holes(rng), Vec(0.5, 0.5), rng);
  }
}

}  // namespace
}  // namespace gridloc
