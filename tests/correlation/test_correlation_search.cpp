// Tests of engine/src/correlation/search.cpp: the padded fast score against the reference
// score, and the exhaustive / multiresolution searches against brute force.
#include "gridloc/engine/correlation/search.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "gridloc/sensors/rng.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

int uniform_int(Rng& rng, int lo, int hi) {  // inclusive
  return lo + static_cast<int>(rng.uniform() * (hi - lo + 1));
}

EvidenceGrid random_global(Rng& rng, int w, int h) {
  GridGeometry g;
  g.resolution = 0.1;
  g.width = w;
  g.height = h;
  EvidenceGrid e(g, 0.0f);
  for (float& v : e.cells) v = static_cast<float>(uniform_int(rng, -1, 1));
  return e;
}

/// Sparse local grid of `n` distinct cells within `extent`, sorted by (dy, dx), with values
/// like the sonar model's (+1/n1, -1/n2) or small integers when `integer` (to make ties).
SparseLocalGrid random_local(Rng& rng, int n, int extent, bool integer) {
  std::set<std::pair<int, int>> cells;  // (dy, dx)
  while (static_cast<int>(cells.size()) < n) {
    cells.insert({uniform_int(rng, -extent, extent), uniform_int(rng, -extent, extent)});
  }
  SparseLocalGrid l;
  for (const auto& [dy, dx] : cells) {
    l.dx.push_back(dx);
    l.dy.push_back(dy);
    float v;
    if (integer) {
      v = static_cast<float>(uniform_int(rng, 0, 1) * 2 - 1);
    } else {
      const int denom = uniform_int(rng, 1, 23);
      v = (rng.uniform() < 0.4 ? 1.0f : -1.0f) / static_cast<float>(denom);
    }
    l.value.push_back(v);
  }
  return l;
}

TEST(PadGrid, CopiesTheGridInsideZeroPadding) {
  Rng rng(5);
  const EvidenceGrid g = random_global(rng, 7, 4);
  const PaddedGrid p = pad_grid(g, 3);
  EXPECT_EQ(p.pad, 3);
  EXPECT_EQ(p.width, 7);
  EXPECT_EQ(p.height, 4);
  ASSERT_EQ(p.grid.width(), 13);
  ASSERT_EQ(p.grid.height(), 10);
  for (int iy = 0; iy < 10; ++iy) {
    for (int ix = 0; ix < 13; ++ix) {
      const bool inside = ix >= 3 && ix < 10 && iy >= 3 && iy < 7;
      EXPECT_EQ(p.cell(p.grid.geometry.index(ix, iy)), inside ? g.at(ix - 3, iy - 3) : 0.0f)
          << ix << "," << iy;
    }
  }
}

constexpr ArcRule kRules[] = {ArcRule::Neutral, ArcRule::Signed};

TEST(PadGrid, ArcViewClampsFreeCellsUnderTheNeutralRule) {
  Rng rng(6);
  const EvidenceGrid g = random_global(rng, 5, 6);
  const PaddedGrid neutral = pad_grid(g, 2, ArcRule::Neutral);
  const PaddedGrid signed_ = pad_grid(g, 2, ArcRule::Signed);
  ASSERT_EQ(neutral.cell_count(), 9u * 10u);
  for (std::size_t i = 0; i < neutral.cell_count(); ++i) {
    EXPECT_EQ(neutral.arc_cell(i), std::max(neutral.cell(i), 0.0f));
    EXPECT_EQ(signed_.arc_cell(i), signed_.cell(i));
  }
  EXPECT_EQ(neutral.float_cells(), signed_.float_cells());
  EXPECT_EQ(neutral.arc_float_cells().size(), neutral.cell_count());
}

// The cells are kept once: as int8 where they are whole multiples of 1 / int8_scale (a
// -1/0/1 grid; no float copy), as floats otherwise. The arc view is a copy only where it
// differs from the grid: a Neutral grid with free (negative) cells; a grid without
// negatives (a likelihood field with free_value 0) or the Signed rule reads the grid's own.
TEST(PadGrid, KeepsEachGridOnceAndTheArcViewOnlyWhereItDiffers) {
  Rng rng(7);
  const EvidenceGrid with_free = random_global(rng, 5, 6);
  ASSERT_TRUE(std::any_of(with_free.cells.begin(), with_free.cells.end(),
                          [](float v) { return v < 0.0f; }));
  EvidenceGrid no_free = with_free;
  for (float& v : no_free.cells) v = std::max(v, 0.0f);
  const PaddedGrid neutral = pad_grid(with_free, 2, ArcRule::Neutral);
  ASSERT_TRUE(neutral.ternary());
  EXPECT_FALSE(neutral.has_floats());  // no float copy
  EXPECT_FALSE(neutral.arc_is_grid);
  EXPECT_FALSE(neutral.arc_cells8.empty());
  for (const PaddedGrid& own :
       {pad_grid(with_free, 2, ArcRule::Signed), pad_grid(no_free, 2, ArcRule::Neutral)}) {
    EXPECT_TRUE(own.arc_is_grid);
    EXPECT_TRUE(own.arc_cells8.empty());
    EXPECT_EQ(own.arc_view8().data(), own.grid8.data());
  }
  EXPECT_EQ(pad_grid(no_free, 2, ArcRule::Neutral).arc_float_cells(), neutral.arc_float_cells());
  // Floats too when asked (a sonar ring's float cones read them): the same values.
  const PaddedGrid both = pad_grid(with_free, 2, ArcRule::Neutral, PaddedCells::FloatsToo);
  ASSERT_TRUE(both.has_floats());
  EXPECT_EQ(both.grid8, neutral.grid8);
  EXPECT_EQ(both.float_cells(), neutral.float_cells());
  EXPECT_EQ(both.arc_float_cells(), neutral.arc_float_cells());
  // Values no int8 scale holds stay floats, the arc view its own copy under Neutral.
  EvidenceGrid fractions = with_free;
  for (float& v : fractions.cells) v *= 0.3f;
  const PaddedGrid floats = pad_grid(fractions, 2, ArcRule::Neutral);
  EXPECT_FALSE(floats.has_int8());
  EXPECT_EQ(floats.grid.cells.size(), floats.cell_count());
  EXPECT_EQ(floats.arc_cells.size(), floats.cell_count());
  for (std::size_t i = 0; i < floats.cell_count(); ++i) {
    EXPECT_EQ(floats.arc_cell(i), std::max(floats.cell(i), 0.0f));
  }
}

TEST(PadGrid, NegativeOrHugePaddingIsAnError) {
  GridGeometry geo;
  geo.width = 4;
  geo.height = 4;
  const EvidenceGrid g(geo, 0.0f);
  test::expect_error([&] { pad_grid(g, -1); }, {"pad = -1", ">= 0"});
  test::expect_error([&] { pad_grid(g, 40000); }, {"too large", "2^31"});
}

TEST(Place, ArcCellsFirstThenFreeCellsEachInLocalOrder) {
  SparseLocalGrid l;
  l.dx = {0, 1, -2, 3, 0};
  l.dy = {-1, -1, 0, 0, 2};
  l.value = {0.5f, -0.25f, -0.125f, 0.5f, -1.0f};
  GridGeometry geo;
  geo.width = 4;
  geo.height = 4;
  const PaddedGrid p = pad_grid(EvidenceGrid(geo, 0.0f), 3);  // padded width 10
  const PlacedLocalGrid placed = place(l, p);
  EXPECT_EQ(placed.arc_count, 2u);
  EXPECT_EQ(placed.value, (std::vector<float>{0.5f, 0.5f, -0.25f, -0.125f, -1.0f}));
  EXPECT_EQ(placed.offset, (std::vector<std::int32_t>{-10, 3, -9, -2, 20}));
  EXPECT_EQ(placed.fixed_shift, 3);  // every value a multiple of 1/8
  EXPECT_EQ(placed.fixed, (std::vector<std::int32_t>{4, 4, -2, -1, -8}));
}

/// The (offset, value) pairs of cells [begin, end) of a placed grid, sorted by offset.
std::vector<std::pair<std::int32_t, float>> cells_of(const PlacedLocalGrid& p, std::size_t begin,
                                                     std::size_t end) {
  std::vector<std::pair<std::int32_t, float>> cells;
  for (std::size_t k = begin; k < end; ++k) cells.emplace_back(p.offset[k], p.value[k]);
  std::sort(cells.begin(), cells.end());
  return cells;
}

// place_points builds the cells place(rasterize_points(...)) builds, bit for bit (the order
// within the arc and the free group may differ).
TEST(Place, PointsEqualPlacedRasterizedPoints) {
  Rng rng(31);
  for (int c = 0; c < 300; ++c) {
    RangeScan scan;
    scan.max_range = 1.0 + rng.uniform(0.0, 5.0);
    const int beams = uniform_int(rng, 1, 120);
    for (int k = 0; k < beams; ++k) {
      scan.angles.push_back(rng.uniform(-3.2, 3.2));
      // Some beams without a return, some very short; at least one return.
      const double r =
          k == 0 || rng.uniform(0.0, 1.0) < 0.9 ? rng.uniform(0.0, scan.max_range) : scan.max_range;
      scan.ranges.push_back(r);
    }
    const double res = c % 2 == 0 ? 0.05 : 0.1;
    const ScanModelOptions model{c % 3 == 0 ? ScanModel::Hits : ScanModel::Samples,
                                 uniform_int(rng, 1, 7)};
    const ScanPoints points = scan_points(scan, model);
    GridGeometry geo;
    geo.resolution = res;
    geo.width = uniform_int(rng, 1, 30);
    geo.height = uniform_int(rng, 1, 30);
    const PaddedGrid g =
        pad_grid(EvidenceGrid(geo, 0.0f), static_cast<int>(std::ceil(scan.max_range / res)) + 3);
    const double theta = rng.uniform(-4.0, 4.0);
    const PlacedLocalGrid a = place_points(points, theta, g);
    const PlacedLocalGrid b = place(rasterize_points(points, theta, res), g);
    ASSERT_EQ(a.arc_count, b.arc_count) << "case " << c;
    EXPECT_EQ(cells_of(a, 0, a.arc_count), cells_of(b, 0, b.arc_count)) << "case " << c;
    EXPECT_EQ(cells_of(a, a.arc_count, a.offset.size()), cells_of(b, b.arc_count, b.offset.size()))
        << "case " << c;
    EXPECT_EQ(a.fixed_shift, b.fixed_shift) << "case " << c;
  }
}

// Every way a padded grid keeps its cells scores alike: int8 alone (a float local grid then
// reads the floats they stand for: cast at scale 1, decoded at a likelihood field's 127) or
// the floats too, on -1/0/1 grids and on grids of multiples of 1/127. On the latter a
// fixed-point local grid's exact integer sum is divided by 127 once (score()), so only a
// float local grid's score is the reference's bit for bit there.
TEST(Score, FastScoreEqualsReferenceExactly) {
  Rng rng(2024);
  int compared = 0;
  for (int c = 0; c < 60; ++c) {
    const int w = uniform_int(rng, 1, 20), h = uniform_int(rng, 1, 20);
    EvidenceGrid g = random_global(rng, w, h);
    if (c % 3 == 1) {  // levels of a likelihood field: k / 127
      for (float& v : g.cells) v = static_cast<float>(v * uniform_int(rng, 0, 127)) / 127.0f;
    }
    const int extent = uniform_int(rng, 0, 6);
    const int side = 2 * extent + 1;
    const SparseLocalGrid l =
        random_local(rng, uniform_int(rng, 1, std::min(40, side * side)), extent, c % 5 == 0);
    const int pad = std::max(l.extent(), extent) + uniform_int(rng, 0, 2);
    for (ArcRule rule : kRules) {
      const PaddedGrid compact = pad_grid(g, pad, rule, PaddedCells::Int8WhereExact);
      const PaddedGrid floats = pad_grid(g, pad, rule, PaddedCells::FloatsToo);
      ASSERT_TRUE(compact.has_int8() && !compact.has_floats()) << c;
      ASSERT_TRUE(floats.has_int8() && floats.has_floats()) << c;
      const PlacedLocalGrid placed = place(l, compact);
      const bool exact = compact.ternary() || placed.fixed_shift < 0;
      for (int cy = 0; cy < h; ++cy) {
        for (int cx = 0; cx < w; ++cx) {
          const double fast = score(compact, placed, cx, cy);
          EXPECT_EQ(score(floats, placed, cx, cy), fast)
              << "case " << c << " (" << cx << ", " << cy << ")";
          if (exact) {
            EXPECT_EQ(fast, score_reference(g, l, cx, cy, rule))
                << "case " << c << " rule " << static_cast<int>(rule) << " cell (" << cx << ", "
                << cy << ")";
            ++compared;
          }
        }
      }
    }
  }
  EXPECT_GT(compared, 2500);
}

TEST(Score, ReferenceByHand) {
  GridGeometry geo;
  geo.width = 3;
  geo.height = 2;
  EvidenceGrid g(geo, 0.0f);
  g.cells = {1, -1, 0,  //
             0, 1,  1};
  SparseLocalGrid l;
  l.dx = {0, 1, -1, 5};
  l.dy = {0, 0, 1, 0};
  l.value = {0.5f, -0.25f, 2.0f, 100.0f};
  // At (1, 0): the arc cell 0.5 lies on free (1,0) = -1: -0.5 when signed, 0 when neutral;
  // (2,0) = 0 and (0,1) = 0 add nothing; (6,0) is outside.
  EXPECT_EQ(score_reference(g, l, 1, 0, ArcRule::Signed), -0.5);
  EXPECT_EQ(score_reference(g, l, 1, 0, ArcRule::Neutral), 0.0);
  EXPECT_EQ(score_reference(g, l, 1, 0), 0.0);  // neutral is the default
  // At (0, 0): (0,0) = 1 -> 0.5; free cell -0.25 on (1,0) = -1 -> +0.25 under both rules;
  // (-1,1) and (5,0) are outside.
  EXPECT_EQ(score_reference(g, l, 0, 0, ArcRule::Signed), 0.75);
  EXPECT_EQ(score_reference(g, l, 0, 0, ArcRule::Neutral), 0.75);
  // At (1, 1)... (1,1) = 1 -> 0.5; (2,1) = 1 -> -0.25; (0,2) outside.
  EXPECT_EQ(score_reference(g, l, 1, 1, ArcRule::Signed), 0.25);
  for (ArcRule rule : kRules) {
    const PaddedGrid p = pad_grid(g, 5, rule);
    EXPECT_EQ(score(p, place(l, p), 0, 0), 0.75);
    EXPECT_EQ(score(p, place(l, p), 1, 0), rule == ArcRule::Signed ? -0.5 : 0.0);
  }
}

struct Brute {
  LatticePose best;
  std::size_t count = 0;
};

Brute brute_force(const Lattice& lat, const EvidenceGrid& g,
                  const std::vector<SparseLocalGrid>& locals, ArcRule rule) {
  Brute b;
  bool first = true;
  for (int it = 0; it < lat.headings; ++it) {
    for (int iy = lat.y0; iy <= lat.y1; ++iy) {
      for (int ix = lat.x0; ix <= lat.x1; ++ix) {
        const double s = score_reference(g, locals[static_cast<std::size_t>(it)], ix, iy, rule);
        ++b.count;
        if (first || s > b.best.score) {  // strict: ties keep the lowest (it, iy, ix)
          b.best = {ix, iy, it, s};
          first = false;
        }
      }
    }
  }
  return b;
}

TEST(SearchExhaustive, PicksTheBruteForceMaximumWithLowestIndexOnTies) {
  Rng rng(77);
  for (int c = 0; c < 50; ++c) {
    const int w = uniform_int(rng, 3, 18), h = uniform_int(rng, 3, 18);
    const EvidenceGrid g = random_global(rng, w, h);
    const bool integer = c % 2 == 0;  // integer values make many ties
    std::vector<SparseLocalGrid> locals;
    const int headings = uniform_int(rng, 1, 4);
    int extent = 0;
    for (int it = 0; it < headings; ++it) {
      locals.push_back(random_local(rng, uniform_int(rng, 1, integer ? 3 : 20), 4, integer));
      extent = std::max(extent, locals.back().extent());
    }
    const ArcRule rule = c % 3 == 0 ? ArcRule::Signed : ArcRule::Neutral;
    const PaddedGrid padded = pad_grid(g, extent, rule);
    Lattice lat;
    lat.x0 = uniform_int(rng, 0, w - 1);
    lat.x1 = uniform_int(rng, lat.x0, w - 1);
    lat.y0 = uniform_int(rng, 0, h - 1);
    lat.y1 = uniform_int(rng, lat.y0, h - 1);
    lat.headings = headings;
    lat.theta0 = 0.0;
    lat.step_theta = 1.0;  // heading index it has theta = it: make_local picks locals[it]
    // make_local takes the heading (and, in newer engines, more arguments it may ignore).
    SearchLevel level{&padded, [&](double theta, const auto&...) {
                        return locals[static_cast<std::size_t>(std::lround(theta))];
                      }};

    const SearchResult r = search_exhaustive(lat, level);
    const Brute b = brute_force(lat, g, locals, rule);
    EXPECT_EQ(std::tie(r.best.it, r.best.iy, r.best.ix), std::tie(b.best.it, b.best.iy, b.best.ix))
        << "case " << c;
    EXPECT_EQ(r.best.score, b.best.score) << "case " << c;
    EXPECT_EQ(r.scored.size(), b.count);
    EXPECT_EQ(r.poses_scored, static_cast<long long>(b.count));
    long long cells = 0;
    for (const auto& p : r.scored) {
      cells += static_cast<long long>(locals[static_cast<std::size_t>(p.it)].size());
      EXPECT_EQ(p.score,
                score_reference(g, locals[static_cast<std::size_t>(p.it)], p.ix, p.iy, rule));
    }
    EXPECT_EQ(r.cells_scored, cells);

    // A single-level multiresolution search is the exhaustive search.
    const SearchResult m = search_multires(lat, {level}, 3);
    EXPECT_EQ(std::tie(m.best.it, m.best.iy, m.best.ix), std::tie(r.best.it, r.best.iy, r.best.ix))
        << "case " << c;
    EXPECT_EQ(m.best.score, r.best.score);
  }
}

TEST(SearchExhaustive, AllTiesGoToTheFirstLatticePose) {
  GridGeometry geo;
  geo.width = 6;
  geo.height = 5;
  const EvidenceGrid g(geo, 0.0f);
  const PaddedGrid padded = pad_grid(g, 2);
  SparseLocalGrid l;
  l.dx = {0, 1};
  l.dy = {0, -2};
  l.value = {1.0f, -1.0f};
  Lattice lat;
  lat.x0 = 2;
  lat.x1 = 5;
  lat.y0 = 1;
  lat.y1 = 4;
  lat.headings = 3;
  lat.step_theta = 0.1;
  const SearchResult r =
      search_exhaustive(lat, {&padded, [&](double, const auto&...) { return l; }});
  EXPECT_EQ(r.best.ix, 2);
  EXPECT_EQ(r.best.iy, 1);
  EXPECT_EQ(r.best.it, 0);
  EXPECT_EQ(r.best.score, 0.0);
  EXPECT_EQ(r.poses_scored, 4 * 4 * 3);
}

TEST(SearchMultires, FindsAnIsolatedPeakThroughCoarseLevels) {
  // A global grid with one +1 cell; the local grid is one +1 cell at the robot. The coarse
  // level (2x cells) holds the block containing the peak; the fine level must find it.
  GridGeometry fine_geo;
  fine_geo.resolution = 0.1;
  fine_geo.width = 16;
  fine_geo.height = 12;
  EvidenceGrid fine(fine_geo, 0.0f);
  fine.at(11, 7) = 1.0f;
  GridGeometry coarse_geo = fine_geo;
  coarse_geo.resolution = 0.2;
  coarse_geo.width = 8;
  coarse_geo.height = 6;
  EvidenceGrid coarse(coarse_geo, 0.0f);
  coarse.at(5, 3) = 1.0f;
  const PaddedGrid pf = pad_grid(fine, 1), pc = pad_grid(coarse, 1);
  SparseLocalGrid l;
  l.dx = {0};
  l.dy = {0};
  l.value = {1.0f};
  Lattice lat;
  lat.x0 = 0;
  lat.x1 = 15;
  lat.y0 = 0;
  lat.y1 = 11;
  lat.headings = 2;
  lat.step_theta = 0.1;
  auto make = [&](double, const auto&...) { return l; };
  const SearchResult r = search_multires(lat, {{&pf, make}, {&pc, make}}, 2);
  EXPECT_EQ(r.best.ix, 11);
  EXPECT_EQ(r.best.iy, 7);
  EXPECT_EQ(r.best.it, 0);
  EXPECT_EQ(r.best.score, 1.0);
  // Coarse: the whole 8x6x2 lattice; fine: children of the 2 kept poses, far fewer than the
  // 16x12x2 exhaustive lattice.
  EXPECT_LT(r.poses_scored, 8 * 6 * 2 + 16 * 12 * 2);
  EXPECT_GT(r.poses_scored, 8 * 6 * 2);
}

}  // namespace
}  // namespace gridloc
