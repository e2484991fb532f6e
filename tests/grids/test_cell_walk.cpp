// Tests of grids/include/gridloc/grids/cell_walk.hpp against brute force: the walk visits,
// in order, exactly the cells that dense samples of the ray fall in, each cell once, and
// step_towards always arrives at the end cell.
#include "gridloc/grids/cell_walk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace gridloc {
namespace {

using Cell = std::pair<int, int>;

/// The distinct cells that samples every 1e-4 along the ray from o in direction d, up to
/// parameter `length`, fall in, in order.
std::vector<Cell> sampled_cells(double ox, double oy, double dx, double dy, double length) {
  std::vector<Cell> cells;
  for (double t = 0.0; t <= length; t += 1e-4) {
    const Cell c{static_cast<int>(std::floor(ox + t * dx)),
                 static_cast<int>(std::floor(oy + t * dy))};
    if (cells.empty() || cells.back() != c) cells.push_back(c);
  }
  return cells;
}

TEST(CellWalk, VisitsTheCellsTheRayCrossesInOrder) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0),
      angle(-std::numbers::pi, std::numbers::pi);
  for (int k = 0; k < 300; ++k) {
    const double ox = coordinate(rng), oy = coordinate(rng), a = angle(rng);
    const double dx = std::cos(a), dy = std::sin(a), length = 6.0;
    CellWalk walk(ox, oy, dx, dy);
    std::vector<Cell> walked;
    while (walk.t <= length) {
      walked.push_back({walk.ix, walk.iy});
      walk.step();
    }
    const std::vector<Cell> sampled = sampled_cells(ox, oy, dx, dy, length);
    // The samples miss a cell only where the ray clips its corner by under 1e-4: each walked
    // cell is a neighbour of the last, and every sampled cell is walked, in the same order.
    for (std::size_t i = 1; i < walked.size(); ++i) {
      EXPECT_EQ(std::abs(walked[i].first - walked[i - 1].first) +
                    std::abs(walked[i].second - walked[i - 1].second),
                1)
          << k;
    }
    std::size_t next = 0;
    for (const Cell& c : sampled) {
      while (next < walked.size() && walked[next] != c) ++next;
      ASSERT_LT(next, walked.size()) << "case " << k << ": a sampled cell was not walked";
    }
  }
}

TEST(CellWalk, AxisRaysStepOneCellAtATime) {
  CellWalk east(2.5, 3.5, 1.0, 0.0);
  east.step();
  EXPECT_EQ(east.ix, 3);
  EXPECT_EQ(east.iy, 3);
  EXPECT_DOUBLE_EQ(east.t, 0.5);
  CellWalk south(2.5, 3.5, 0.0, -2.0);  // the parameter counts the direction's lengths
  south.step();
  south.step();
  EXPECT_EQ(south.ix, 2);
  EXPECT_EQ(south.iy, 1);
  EXPECT_DOUBLE_EQ(south.t, 0.75);
}

TEST(CellWalk, StepTowardsAlwaysArrivesAtTheEndCell) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> coordinate(-30.0, 30.0);
  for (int k = 0; k < 1000; ++k) {
    const double ax = coordinate(rng), ay = coordinate(rng);
    const double bx = k % 10 == 0 ? ax : coordinate(rng), by = coordinate(rng);
    const int ex = static_cast<int>(std::floor(bx)), ey = static_cast<int>(std::floor(by));
    CellWalk walk(ax, ay, bx - ax, by - ay);
    const int steps = std::abs(ex - walk.ix) + std::abs(ey - walk.iy);
    for (int s = 0; s < steps; ++s) walk.step_towards(ex, ey);
    EXPECT_EQ(walk.ix, ex) << k;
    EXPECT_EQ(walk.iy, ey) << k;
  }
}

}  // namespace
}  // namespace gridloc
