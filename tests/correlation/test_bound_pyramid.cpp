// Tests of the bound pyramid and block bounds of engine/src/correlation/branch_and_bound.cpp:
// pooled levels with the padded geometry, the depth a lattice needs, and block bounds against
// exact scores on random grids and local grids with fixed seeds.
#include "gridloc/engine/correlation/branch_and_bound.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "correlation/search_cases.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;  // the shared search cases, random draws and checks

/// The oracle: the max of the arc view and the min of the grid over the block of 2^level
/// cells at (x, y), clipped at the padded grid's edge.
std::pair<float, float> pooled_at(const PaddedGrid& padded, int level, int x, int y) {
  const int w = padded.grid.width(), h = padded.grid.height();
  float hi = -1e30f, lo = 1e30f;
  for (int yy = y; yy < std::min(h, y + (1 << level)); ++yy) {
    for (int xx = x; xx < std::min(w, x + (1 << level)); ++xx) {
      hi = std::max(hi, padded.arc_cell(padded.grid.geometry.index(xx, yy)));
      lo = std::min(lo, padded.cell(padded.grid.geometry.index(xx, yy)));
    }
  }
  return {hi, lo};
}

TEST(BoundPyramid, LevelsArePooledGridsWithThePaddedGeometry) {
  std::mt19937 rng(11);
  const EvidenceGrid g = make_grid(rng, 9, 7, GridKind::Floats);
  const PaddedGrid padded = pad_grid(g, 3, ArcRule::Neutral);
  const BoundPyramid p = make_bound_pyramid(padded, 3);
  ASSERT_EQ(p.depth(), 3);
  EXPECT_TRUE(p.arc_max[0].cells.empty());
  EXPECT_TRUE(p.grid_min[0].cells.empty());
  EXPECT_EQ(p.pad, 3);
  EXPECT_EQ(p.width, 9);
  EXPECT_EQ(p.height, 7);
  const int w = padded.grid.width(), h = padded.grid.height();
  for (int level = 1; level <= 3; ++level) {
    const auto& mx = p.arc_max[static_cast<std::size_t>(level)];
    const auto& mn = p.grid_min[static_cast<std::size_t>(level)];
    ASSERT_EQ(mx.width(), w);
    ASSERT_EQ(mn.height(), h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const auto [hi, lo] = pooled_at(padded, level, x, y);
        EXPECT_EQ(mx.at(x, y), hi);
        EXPECT_EQ(mn.at(x, y), lo);
      }
    }
  }
  EXPECT_EQ(make_bound_pyramid(padded, 0).depth(), 0);
  EXPECT_THROW(make_bound_pyramid(padded, -1), Error);
}

// An evidence grid (-1/0/1) keeps its levels as int8 only: the pooled values, and its float
// levels hold the geometry and no cells.
TEST(BoundPyramid, ATernaryGridKeepsItsLevelsAsInt8Only) {
  std::mt19937 rng(12);
  const EvidenceGrid g = make_grid(rng, 11, 6, GridKind::Ternary);
  const PaddedGrid padded = pad_grid(g, 2, ArcRule::Neutral);
  const BoundPyramid p = make_bound_pyramid(padded, 3);
  ASSERT_TRUE(p.ternary());
  ASSERT_EQ(p.arc_max8.size(), 4u);
  const int w = padded.grid.width(), h = padded.grid.height();
  for (int level = 1; level <= 3; ++level) {
    const auto l = static_cast<std::size_t>(level);
    EXPECT_TRUE(p.arc_max[l].cells.empty());
    EXPECT_TRUE(p.grid_min[l].cells.empty());
    EXPECT_EQ(p.arc_max[l].width(), w);
    EXPECT_EQ(p.grid_min[l].height(), h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const auto [hi, lo] = pooled_at(padded, level, x, y);
        const std::size_t k = padded.grid.geometry.index(x, y);
        EXPECT_EQ(p.arc_max8[l][k], static_cast<std::int8_t>(hi));
        EXPECT_EQ(p.grid_min8[l][k], static_cast<std::int8_t>(lo));
      }
    }
  }
}

// Max-pooled levels only: the arc view's levels as before, and one level of the grid's
// minimum standing for every min-pooled level (memory and pooling halved for a laser's hits);
// an int8 pyramid (ternary or a likelihood field's) keeps no float level.
TEST(BoundPyramid, MaxOnlyKeepsOneLevelOfTheGridsMinimum) {
  std::mt19937 rng(13);
  for (GridKind kind : {GridKind::Ternary, GridKind::Floats, GridKind::Field}) {
    const EvidenceGrid g = make_grid(rng, 10, 8, kind);
    const PaddedGrid padded = pad_grid(g, 2, ArcRule::Neutral);
    const BoundPyramid both = make_bound_pyramid(padded, 3);
    const BoundPyramid p = make_bound_pyramid(padded, 3, PyramidLevels::MaxOnly);
    EXPECT_TRUE(both.min_levels);
    EXPECT_FALSE(p.min_levels);
    ASSERT_EQ(p.depth(), 3);
    EXPECT_EQ(p.min_level(3), 1u);
    EXPECT_EQ(p.grid_min_all, both.grid_min_all);
    EXPECT_EQ(p.arc_max8, both.arc_max8);
    const std::size_t cells = padded.cell_count();
    if (p.has_int8()) {
      ASSERT_EQ(p.grid_min8.size(), 2u);  // level 0 and the minimum's level
      // Level 0 is read from the padded grid's own int8 cells, not kept a second time.
      EXPECT_TRUE(p.grid_min8[0].empty());
      EXPECT_TRUE(p.arc_max8[0].empty());
      for (std::size_t k = 0; k < cells; ++k) {
        EXPECT_EQ(p.grid_min8[1][k], static_cast<std::int8_t>(p.grid_min_all * p.int8_scale));
      }
    }
    EXPECT_EQ(p.float_levels, kind == GridKind::Floats);
    EXPECT_EQ(p.has_int8(), kind != GridKind::Floats);
    for (int level = 1; level <= 3; ++level) {
      const auto l = static_cast<std::size_t>(level);
      EXPECT_EQ(p.arc_max[l].cells.empty(), !p.float_levels) << level;
      if (p.float_levels) {
        EXPECT_EQ(p.arc_max[l].cells, both.arc_max[l].cells);
      }
      EXPECT_EQ(p.grid_min[l].cells.empty(), level > 1 || !p.float_levels) << level;
    }
    if (p.float_levels) {
      for (float v : p.grid_min[1].cells) EXPECT_EQ(v, p.grid_min_all);
    }
  }
}

TEST(BoundDepthFor, CoversTheLatticeInOneBlock) {
  Lattice lat;
  lat.x0 = 3, lat.x1 = 3, lat.y0 = 5, lat.y1 = 5;
  EXPECT_EQ(bound_depth_for(lat), 0);
  lat.x1 = 4;
  EXPECT_EQ(bound_depth_for(lat), 1);
  lat.x1 = 19;  // 17 columns
  EXPECT_EQ(bound_depth_for(lat), 5);
  lat.x1 = 18, lat.y1 = 45;  // 41 rows
  EXPECT_EQ(bound_depth_for(lat), 6);
}

TEST(BlockBound, BoundsEveryPoseOfItsBlockExactly) {
  std::mt19937 rng(7);
  long long checked = 0;
  for (int c = 0; c < 60; ++c) {
    const int w = uniform_int(rng, 1, 24), h = uniform_int(rng, 1, 24);
    const auto kind = static_cast<GridKind>(c % static_cast<int>(GridKind::Count));
    const EvidenceGrid g = make_grid(rng, w, h, kind);
    const int extent = uniform_int(rng, 0, 8);
    const SparseLocalGrid l = make_local(rng, uniform_int(rng, 1, 40), extent, c % 3);
    for (ArcRule rule : kRules) {
      const PaddedGrid padded = pad_grid(g, extent + uniform_int(rng, 0, 2), rule);
      const PlacedLocalGrid placed = place(l, padded);
      for (PyramidLevels levels : {PyramidLevels::MaxAndMin, PyramidLevels::MaxOnly}) {
        const BoundPyramid p = make_bound_pyramid(padded, 4, levels);
        for (int level = 1; level <= 4; ++level) {
          const int side = 1 << level;
          for (int by = 0; by < h; ++by) {
            for (int bx = 0; bx < w; ++bx) {
              const double bound = block_bound(p, placed, level, bx, by);
              for (int y = by; y < std::min(h, by + side); ++y) {
                for (int x = bx; x < std::min(w, bx + side); ++x) {
                  ASSERT_GE(bound, score(padded, placed, x, y))
                      << "case " << c << " level " << level << " block (" << bx << ", " << by
                      << ") pose (" << x << ", " << y << ") min levels " << p.min_levels;
                  ++checked;
                }
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 200000);
}

}  // namespace
}  // namespace gridloc
