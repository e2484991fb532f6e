// Tests of grids/src/pooling.cpp: the O(cells) sliding-window max / min pooling against the
// plain reference loops, on random grids with fixed seeds.
#include "gridloc/grids/pooling.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "random_cases.hpp"

namespace gridloc {
namespace {

using test::uniform_int;

Grid<float> random_grid(std::mt19937& rng, int w, int h) {
  GridGeometry g;
  g.width = w;
  g.height = h;
  Grid<float> grid(g, 0.0f);
  const bool ternary = rng() % 2 == 0;
  for (float& v : grid.cells) {
    v = ternary ? static_cast<float>(uniform_int(rng, -1, 1))
                : static_cast<float>(static_cast<double>(rng()) / 4294967296.0 * 4.0 - 2.0);
  }
  return grid;
}

TEST(Pooling, ByHand) {
  GridGeometry geo;
  geo.width = 4;
  geo.height = 3;
  Grid<float> g(geo, 0.0f);
  g.cells = {1,  5,  2, 0,  // row 0
             3,  -1, 4, 7,  // row 1
             -2, 6,  0, 1};
  const Grid<float> mx = max_pool(g, 2);
  EXPECT_EQ(mx.cells, (std::vector<float>{5, 5, 7, 7,  //
                                          6, 6, 7, 7,  //
                                          6, 6, 1, 1}));
  const Grid<float> mn = min_pool(g, 2);
  EXPECT_EQ(mn.cells, (std::vector<float>{-1, -1, 0, 0,  //
                                          -2, -1, 0, 1,  //
                                          -2, 0, 0, 1}));
  EXPECT_EQ(max_pool(g, 1).cells, g.cells);
  EXPECT_EQ(max_pool(g, 100).cells[0], 7.0f);
  EXPECT_EQ(min_pool(g, 100).cells[0], -2.0f);
}

TEST(Pooling, FastEqualsReferenceOnRandomGrids) {
  std::mt19937 rng(4242);
  int compared = 0;
  for (int c = 0; c < 400; ++c) {
    const int w = uniform_int(rng, 1, 40), h = uniform_int(rng, 1, 40);
    const Grid<float> g = random_grid(rng, w, h);
    const int size = c % 4 == 0 ? uniform_int(rng, 1, 45) : (1 << uniform_int(rng, 0, 5));
    const Grid<float> mx = max_pool(g, size), mn = min_pool(g, size);
    ASSERT_EQ(mx.width(), w);
    ASSERT_EQ(mx.height(), h);
    EXPECT_EQ(mx.cells, max_pool_reference(g, size).cells) << "case " << c << " size " << size;
    EXPECT_EQ(mn.cells, min_pool_reference(g, size).cells) << "case " << c << " size " << size;
    ++compared;
  }
  EXPECT_EQ(compared, 400);
}

// The vectorized doubling step (MAXPS/MINPS) equals the plain loops: a pyramid built level
// from level is the pyramid pooled from scratch, bit for bit; in place too (the bound
// pyramid's levels, no allocation per level).
TEST(Pooling, DoubledEqualsReferenceOnRandomGrids) {
  for (const bool in_place : {false, true}) {
    std::mt19937 rng(77);
    for (int c = 0; c < 200; ++c) {
      const int w = uniform_int(rng, 1, 70), h = uniform_int(rng, 1, 50);
      const Grid<float> g = random_grid(rng, w, h);
      Grid<float> mx = g, mn = g;
      for (int size = 1; size <= 64; size *= 2) {
        if (in_place) {
          max_pool_doubled_in_place(mx, size);
          min_pool_doubled_in_place(mn, size);
        } else {
          mx = max_pool_doubled(mx, size);
          mn = min_pool_doubled(mn, size);
        }
        const std::string what = "case " + std::to_string(c) + " size " + std::to_string(size) +
                                 (in_place ? " in place" : "");
        EXPECT_EQ(mx.cells, max_pool_reference(g, 2 * size).cells) << what;
        EXPECT_EQ(mn.cells, min_pool_reference(g, 2 * size).cells) << what;
      }
    }
  }
  GridGeometry geo;
  geo.width = geo.height = 2;
  EXPECT_THROW(max_pool_doubled(Grid<float>(geo, 0.0f), 0), Error);
  Grid<float> zero(geo, 0.0f);
  EXPECT_THROW(min_pool_doubled_in_place(zero, 0), Error);
}

// int8 cells pooled in place equal the float reference's pooled values, whole numbers in
// [-127, 127] as a bound pyramid's int8 levels hold them.
TEST(Pooling, DoubledInt8EqualsReferenceOnRandomGrids) {
  std::mt19937 rng(78);
  for (int c = 0; c < 200; ++c) {
    const int w = uniform_int(rng, 1, 70), h = uniform_int(rng, 1, 50);
    GridGeometry geo;
    geo.width = w;
    geo.height = h;
    Grid<float> g(geo, 0.0f);
    for (float& v : g.cells) v = static_cast<float>(uniform_int(rng, -127, 127));
    std::vector<std::int8_t> mx(g.cells.begin(), g.cells.end()), mn = mx;
    for (int size = 1; size <= 64; size *= 2) {
      max_pool_doubled_in_place(mx.data(), w, h, size);
      min_pool_doubled_in_place(mn.data(), w, h, size);
      const Grid<float> hi = max_pool_reference(g, 2 * size), lo = min_pool_reference(g, 2 * size);
      const std::string what = "case " + std::to_string(c) + " size " + std::to_string(size);
      EXPECT_EQ(std::vector<float>(mx.begin(), mx.end()), hi.cells) << what;
      EXPECT_EQ(std::vector<float>(mn.begin(), mn.end()), lo.cells) << what;
    }
  }
  std::int8_t cell = 0;
  EXPECT_THROW(max_pool_doubled_in_place(&cell, 1, 1, 0), Error);
}

// A grid that is zero outside a rectangle, pooled over that rectangle only level after
// level, equals the same grid pooled whole, and the rectangle returned holds every nonzero
// cell (a padded map's pyramid).
TEST(Pooling, DoubledInt8OverTheNonzeroRectangleEqualsTheWholeGrid) {
  std::mt19937 rng(79);
  for (int c = 0; c < 200; ++c) {
    const int w = uniform_int(rng, 1, 90), h = uniform_int(rng, 1, 70);
    CellRect rect{uniform_int(rng, 0, w), uniform_int(rng, 0, h), 0, 0};
    rect.x1 = uniform_int(rng, rect.x0, w);
    rect.y1 = uniform_int(rng, rect.y0, h);
    std::vector<std::int8_t> whole(static_cast<std::size_t>(w) * h, 0);
    for (int y = rect.y0; y < rect.y1; ++y) {
      for (int x = rect.x0; x < rect.x1; ++x) {
        whole[static_cast<std::size_t>(y) * w + x] =
            static_cast<std::int8_t>(uniform_int(rng, -127, 127));
      }
    }
    std::vector<std::int8_t> mx = whole, mn = whole, region_mx = whole, region_mn = whole;
    CellRect mx_rect = rect, mn_rect = rect;
    for (int size = 1; size <= 64; size *= 2) {
      max_pool_doubled_in_place(mx.data(), w, h, size);
      min_pool_doubled_in_place(mn.data(), w, h, size);
      mx_rect = max_pool_doubled_in_place(region_mx.data(), w, h, size, mx_rect);
      mn_rect = min_pool_doubled_in_place(region_mn.data(), w, h, size, mn_rect);
      const std::string what = "case " + std::to_string(c) + " size " + std::to_string(size);
      ASSERT_EQ(region_mx, mx) << what;
      ASSERT_EQ(region_mn, mn) << what;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const bool inside =
              x >= mx_rect.x0 && x < mx_rect.x1 && y >= mx_rect.y0 && y < mx_rect.y1;
          if (!inside) {
            ASSERT_EQ(mx[static_cast<std::size_t>(y) * w + x], 0) << what;
          }
        }
      }
    }
  }
  std::int8_t cell = 0;
  EXPECT_THROW(min_pool_doubled_in_place(&cell, 1, 1, 0, CellRect{0, 0, 1, 1}), Error);
}

TEST(Pooling, KeepsTheGeometry) {
  GridGeometry geo;
  geo.resolution = 0.05;
  geo.origin = {1.0, -2.0};
  geo.width = 3;
  geo.height = 2;
  const Grid<float> p = max_pool(Grid<float>(geo, 1.0f), 4);
  EXPECT_EQ(p.geometry.resolution, 0.05);
  EXPECT_EQ(p.geometry.origin, geo.origin);
  EXPECT_EQ(p.cells, std::vector<float>(6, 1.0f));
}

TEST(Pooling, EmptyGridGivesEmptyGrid) {
  EXPECT_TRUE(max_pool(Grid<float>(), 3).cells.empty());
  EXPECT_TRUE(min_pool(Grid<float>(), 3).cells.empty());
}

TEST(Pooling, RejectsABlockSizeBelowOne) {
  GridGeometry geo;
  geo.width = 2;
  geo.height = 2;
  const Grid<float> g(geo, 0.0f);
  EXPECT_THROW(max_pool(g, 0), Error);
  EXPECT_THROW(min_pool(g, -3), Error);
  try {
    max_pool(g, 0);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("block size must be >= 1, got 0"), std::string::npos);
  }
}

}  // namespace
}  // namespace gridloc
