// Geodesic distances in a grid overlay's OI against Floyd-Warshall over the same 8-connected
// graph on small random maps; the returned paths against the distances.
#include "gridloc/engine/disambiguation/grid_geodesic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "gridloc/engine/disambiguation/grid_overlay.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kSide = 12;
constexpr double kRes = 0.25;

/// A kSide x kSide map at kRes, its cell (0, 0) at (-1.5, -1.5) (so the start frame of the
/// identity hypothesis puts lattice cells on map cells), about 30 % of the cells Occupied.
OccupancyMap random_map(std::mt19937& rng) {
  GridGeometry g;
  g.resolution = kRes;
  g.origin = {-1.5, -1.5};
  g.width = kSide;
  g.height = kSide;
  OccupancyMap map(g, CellState::Free);
  for (CellState& cell : map.cells) {
    if (test::uniform_int(rng, 0, 9) < 3) cell = CellState::Occupied;
  }
  return map;
}

Eigen::Vector2d center(const OccupancyMap& map, int ix, int iy) {
  return map.geometry.origin + map.geometry.cell_center(ix, iy);
}

bool free_at(const OccupancyMap& map, int ix, int iy) {
  return map.geometry.contains(ix, iy) && map.at(ix, iy) == CellState::Free;
}

/// The 4-connected component of free map cells holding `start` (brute force BFS).
std::vector<std::uint8_t> component(const OccupancyMap& map, const Cell& start) {
  std::vector<std::uint8_t> in(map.cells.size(), 0);
  std::deque<Cell> frontier{start};
  in[map.geometry.index(start.ix, start.iy)] = 1;
  while (!frontier.empty()) {
    const Cell c = frontier.front();
    frontier.pop_front();
    for (const Cell n :
         {Cell{c.ix + 1, c.iy}, Cell{c.ix - 1, c.iy}, Cell{c.ix, c.iy + 1}, Cell{c.ix, c.iy - 1}}) {
      if (!free_at(map, n.ix, n.iy) || in[map.geometry.index(n.ix, n.iy)]) continue;
      in[map.geometry.index(n.ix, n.iy)] = 1;
      frontier.push_back(n);
    }
  }
  return in;
}

/// All-pairs distances (Floyd-Warshall) over the cells of `in`: 8-connected, a diagonal only
/// when both side cells are in too, weights kRes x {1, sqrt 2}.
std::vector<double> floyd_warshall(const std::vector<std::uint8_t>& in) {
  const int n = kSide * kSide;
  std::vector<double> d(static_cast<std::size_t>(n) * n, kInf);
  auto at = [&](int a, int b) -> double& { return d[static_cast<std::size_t>(a) * n + b]; };
  auto inside = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < kSide && y < kSide && in[y * kSide + x];
  };
  for (int a = 0; a < n; ++a) {
    if (!in[a]) continue;
    at(a, a) = 0.0;
    const int ax = a % kSide, ay = a / kSide;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !inside(ax + dx, ay + dy)) continue;
        if (dx != 0 && dy != 0 && (!inside(ax + dx, ay) || !inside(ax, ay + dy))) continue;
        at(a, (ay + dy) * kSide + ax + dx) = dx != 0 && dy != 0 ? kRes * std::numbers::sqrt2 : kRes;
      }
    }
  }
  for (int k = 0; k < n; ++k) {
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) at(a, b) = std::min(at(a, b), at(a, k) + at(k, b));
    }
  }
  return d;
}

/// The map cell holding world point p (identity hypothesis: start frame = world).
Cell map_cell(const OccupancyMap& map, const Eigen::Vector2d& p) {
  return map.geometry.cell_of(p.x() - map.geometry.origin.x(), p.y() - map.geometry.origin.y());
}

/// Checks a path: from the source cell's centre to the target's, straight 8-direction runs
/// through component cells (no corner cut), turning at every kept vertex, as long as `length`.
void expect_valid_path(const OccupancyMap& map, const std::vector<std::uint8_t>& in,
                       const std::vector<Eigen::Vector2d>& path, const Eigen::Vector2d& from,
                       const Eigen::Vector2d& to, double length) {
  ASSERT_FALSE(path.empty());
  EXPECT_LT((path.front() - from).norm(), 1e-12);
  EXPECT_LT((path.back() - to).norm(), 1e-12);
  double total = 0.0;
  Cell previous_step{0, 0};
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Eigen::Vector2d cells = (path[k] - path[k - 1]) / kRes;
    const int nx = static_cast<int>(std::lround(cells.x())),
              ny = static_cast<int>(std::lround(cells.y()));
    ASSERT_TRUE(nx == 0 || ny == 0 || std::abs(nx) == std::abs(ny)) << nx << " " << ny;
    const int steps = std::max(std::abs(nx), std::abs(ny));
    ASSERT_GT(steps, 0);
    const Cell step{nx / steps, ny / steps};
    EXPECT_FALSE(step == previous_step) << "collinear vertex kept";
    previous_step = step;
    Cell c = map_cell(map, path[k - 1]);
    for (int s = 0; s < steps; ++s) {
      if (step.ix != 0 && step.iy != 0) {
        EXPECT_TRUE(in[map.geometry.index(c.ix + step.ix, c.iy)]);
        EXPECT_TRUE(in[map.geometry.index(c.ix, c.iy + step.iy)]);
      }
      c = {c.ix + step.ix, c.iy + step.iy};
      ASSERT_TRUE(map.geometry.contains(c.ix, c.iy));
      EXPECT_TRUE(in[map.geometry.index(c.ix, c.iy)]);
    }
    total += (path[k] - path[k - 1]).norm();
  }
  EXPECT_NEAR(total, length, 1e-12);
}

TEST(GridGeodesic, MatchesFloydWarshallOnRandomMaps) {
  std::mt19937 rng(2026);
  for (int trial = 0; trial < 12; ++trial) {
    const OccupancyMap map = random_map(rng);
    int sx = 0, sy = 0;
    do {
      sx = test::uniform_int(rng, 0, kSide - 1);
      sy = test::uniform_int(rng, 0, kSide - 1);
    } while (!free_at(map, sx, sy));
    const Eigen::Vector2d source = center(map, sx, sy) + Eigen::Vector2d(0.03, -0.07);
    const GridOverlay overlay = make_grid_overlay(map, {{0.0, 0.0, 0.0}}, 1.0, source);
    const std::vector<std::uint8_t> in = component(map, {sx, sy});
    const std::vector<double> all = floyd_warshall(in);
    const GridGeodesic geodesic(overlay, source);
    for (int iy = 0; iy < kSide; ++iy) {
      for (int ix = 0; ix < kSide; ++ix) {
        const Eigen::Vector2d target = center(map, ix, iy);
        ASSERT_EQ(overlay.oi_contains(target), in[map.geometry.index(ix, iy)] != 0);
        const double expected = all[static_cast<std::size_t>(sy * kSide + sx) * kSide * kSide +
                                    static_cast<std::size_t>(iy * kSide + ix)];
        const double got = geodesic.distance_to(target + Eigen::Vector2d(-0.1, 0.1));
        if (expected == kInf) {
          EXPECT_EQ(got, kInf);
          EXPECT_TRUE(geodesic.path_to(target).empty());
          continue;
        }
        EXPECT_NEAR(got, expected, 1e-12) << "trial " << trial << " cell " << ix << " " << iy;
        expect_valid_path(map, in, geodesic.path_to(target), center(map, sx, sy), target, got);
      }
    }
  }
}

TEST(GridGeodesic, StraightAndCornerPaths) {
  const OccupancyMap map = test::walled_room(12, 8, 0.5, {0.0, 0.0});  // interior 10 x 6
  const std::vector<Pose2> start{{0.0, 0.0, 0.0}};
  const Eigen::Vector2d source(0.75, 0.75);
  const GridOverlay overlay = make_grid_overlay(map, start, 1.0, source);
  const GridGeodesic geodesic(overlay, source);
  EXPECT_DOUBLE_EQ(geodesic.distance_to({4.75, 0.75}), 4.0);
  EXPECT_EQ(geodesic.path_to({4.75, 0.75}).size(), 2u);  // one straight run
  EXPECT_DOUBLE_EQ(geodesic.distance_to({2.25, 2.25}), 3.0 * 0.5 * std::numbers::sqrt2);
  EXPECT_EQ(geodesic.path_to({0.75, 0.75}).size(), 1u);  // the source itself
  EXPECT_EQ(geodesic.distance_to({0.25, 0.75}), kInf);   // a wall
  EXPECT_TRUE(geodesic.path_to({20.0, 0.75}).empty());   // off the lattice
}

TEST(GridGeodesic, NoCornerCutting) {
  // Two free cells touching only at a corner are not joined.
  OccupancyMap map = test::walled_room(6, 6, 1.0, {0.0, 0.0});
  map.at(2, 1) = CellState::Occupied;
  map.at(1, 2) = CellState::Occupied;
  const GridOverlay overlay = make_grid_overlay(map, {{0.0, 0.0, 0.0}}, 1.0, {3.5, 3.5});
  const GridGeodesic geodesic(overlay, {2.5, 2.5});
  EXPECT_EQ(geodesic.distance_to({1.5, 1.5}), kInf);  // cell (1, 1): not in OI at all
  EXPECT_DOUBLE_EQ(geodesic.distance_to({4.5, 4.5}), 2.0 * std::numbers::sqrt2);
}

TEST(GridGeodesic, SourceOutsideOiThrows) {
  const OccupancyMap map = test::walled_room(12, 8, 0.5, {0.0, 0.0});
  const GridOverlay overlay = make_grid_overlay(map, {{0.0, 0.0, 0.0}}, 1.0, {0.75, 0.75});
  test::expect_error([&] { GridGeodesic(overlay, {0.25, 0.25}); }, {"source", "not in an OI"});
}

}  // namespace
}  // namespace gridloc
