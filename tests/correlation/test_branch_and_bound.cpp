// Tests of engine/src/correlation/branch_and_bound.cpp: block bounds against exact scores, and the
// branch-and-bound search against search_exhaustive, exactly (pose and score bit for bit),
// on random grids, local grids and lattices with fixed seeds, and on grids made of ties; with
// rigid scan points too (heading-interval bounds, threads, exclusion, incumbent, budget).
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

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::random_scan;
using test::uniform_float;
using test::uniform_int;
using test::uniform_real;

constexpr ArcRule kRules[] = {ArcRule::Neutral, ArcRule::Signed};

enum class GridKind { Ternary, Floats, Zero, Constant, Sparse, Periodic, Count };

EvidenceGrid make_grid(std::mt19937& rng, int w, int h, GridKind kind) {
  GridGeometry geo;
  geo.width = w;
  geo.height = h;
  EvidenceGrid g(geo, 0.0f);
  switch (kind) {
    case GridKind::Ternary:
      for (float& v : g.cells) v = static_cast<float>(uniform_int(rng, -1, 1));
      break;
    case GridKind::Floats:
      for (float& v : g.cells) v = uniform_float(rng, -1.0f, 1.0f);
      break;
    case GridKind::Zero:
    case GridKind::Count:
      break;
    case GridKind::Constant: {
      const float c = std::array<float, 4>{1.0f, -1.0f, 0.5f, 0.3f}[rng() % 4];
      for (float& v : g.cells) v = c;
      break;
    }
    case GridKind::Sparse:  // like a thinned map: a few occupied cells, some free, mostly unknown
      for (float& v : g.cells) {
        const int r = uniform_int(rng, 0, 9);
        v = r == 0 ? 1.0f : (r <= 3 ? -1.0f : 0.0f);
      }
      break;
    case GridKind::Periodic: {  // a small tile repeated: equal scores at many translations
      const int px = uniform_int(rng, 1, 4), py = uniform_int(rng, 1, 4);
      std::vector<float> tile(static_cast<std::size_t>(px * py));
      for (float& v : tile) v = static_cast<float>(uniform_int(rng, -1, 1));
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x)
          g.at(x, y) = tile[static_cast<std::size_t>((y % py) * px + x % px)];
      }
      break;
    }
  }
  return g;
}

/// `n` distinct cells within `extent`, sorted by (dy, dx), mixed signs. Values: +-1 (many
/// ties), the sonar model's +-1/k, or arbitrary floats.
SparseLocalGrid make_local(std::mt19937& rng, int n, int extent, int value_kind) {
  const int side = 2 * extent + 1;
  n = std::min(n, side * side);
  std::set<std::pair<int, int>> cells;  // (dy, dx)
  while (static_cast<int>(cells.size()) < n) {
    cells.insert({uniform_int(rng, -extent, extent), uniform_int(rng, -extent, extent)});
  }
  SparseLocalGrid l;
  for (const auto& [dy, dx] : cells) {
    l.dx.push_back(dx);
    l.dy.push_back(dy);
    const float sign = uniform_int(rng, 0, 9) < 4 ? 1.0f : -1.0f;
    float v = sign;
    if (value_kind == 1) v = sign / static_cast<float>(uniform_int(rng, 1, 23));
    if (value_kind == 2) v = sign * uniform_float(rng, 0.01f, 2.0f);
    l.value.push_back(v);
  }
  return l;
}

Lattice make_lattice(std::mt19937& rng, int w, int h, int headings) {
  Lattice lat;
  lat.headings = headings;
  lat.theta0 = 0.0;
  lat.step_theta = 1.0;  // heading index it has theta = it: make_local picks locals[it]
  switch (uniform_int(rng, 0, 4)) {
    case 0:  // the whole map
      lat.x0 = 0, lat.x1 = w - 1, lat.y0 = 0, lat.y1 = h - 1;
      break;
    case 1:  // a single cell
      lat.x0 = lat.x1 = uniform_int(rng, 0, w - 1);
      lat.y0 = lat.y1 = uniform_int(rng, 0, h - 1);
      break;
    case 2: {  // a +-r window around a cell, clipped at the map's edge
      const int r = uniform_int(rng, 0, 12);
      const int cx = uniform_int(rng, 0, w - 1), cy = uniform_int(rng, 0, h - 1);
      lat.x0 = std::max(0, cx - r), lat.x1 = std::min(w - 1, cx + r);
      lat.y0 = std::max(0, cy - r), lat.y1 = std::min(h - 1, cy + r);
      break;
    }
    default:  // any sub-rectangle
      lat.x0 = uniform_int(rng, 0, w - 1), lat.x1 = uniform_int(rng, lat.x0, w - 1);
      lat.y0 = uniform_int(rng, 0, h - 1), lat.y1 = uniform_int(rng, lat.y0, h - 1);
      break;
  }
  return lat;
}

SearchLevel level_of(const PaddedGrid& padded, const std::vector<SparseLocalGrid>& locals) {
  return {&padded, [&locals](double theta, const auto&...) {
            return locals[static_cast<std::size_t>(std::lround(theta))];
          }};
}

/// Runs both searches and checks they agree exactly; returns the branch-and-bound result.
SearchResult expect_same_as_exhaustive(const Lattice& lat, const SearchLevel& level,
                                       const BoundPyramid& pyramid, const std::string& what) {
  const SearchResult e = search_exhaustive(lat, level);
  const SearchResult b = search_branch_and_bound(lat, level, pyramid);
  EXPECT_EQ(b.best.ix, e.best.ix) << what;
  EXPECT_EQ(b.best.iy, e.best.iy) << what;
  EXPECT_EQ(b.best.it, e.best.it) << what;
  EXPECT_EQ(b.best.score, e.best.score) << what;
  // Leaves are lattice poses scored exactly as exhaustive scores them, each once.
  const int nx = lat.x1 - lat.x0 + 1, ny = lat.y1 - lat.y0 + 1;
  EXPECT_EQ(b.poses_scored, static_cast<long long>(b.scored.size())) << what;
  EXPECT_LE(b.poses_scored, e.poses_scored) << what;
  std::vector<char> seen(e.scored.size(), 0);
  for (const auto& p : b.scored) {
    EXPECT_TRUE(p.ix >= lat.x0 && p.ix <= lat.x1 && p.iy >= lat.y0 && p.iy <= lat.y1 && p.it >= 0 &&
                p.it < lat.headings)
        << what;
    const auto k =
        (static_cast<std::size_t>(p.it) * ny + static_cast<std::size_t>(p.iy - lat.y0)) * nx +
        static_cast<std::size_t>(p.ix - lat.x0);
    if (k >= e.scored.size()) continue;
    EXPECT_EQ(p.score, e.scored[k].score) << what;
    EXPECT_FALSE(seen[k]) << what << ": pose scored twice";
    seen[k] = 1;
  }
  return b;
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
        float hi = -1e30f, lo = 1e30f;
        for (int yy = y; yy < std::min(h, y + (1 << level)); ++yy) {
          for (int xx = x; xx < std::min(w, x + (1 << level)); ++xx) {
            hi = std::max(hi, padded.arc_view[padded.grid.geometry.index(xx, yy)]);
            lo = std::min(lo, padded.grid.at(xx, yy));
          }
        }
        EXPECT_EQ(mx.at(x, y), hi);
        EXPECT_EQ(mn.at(x, y), lo);
      }
    }
  }
  EXPECT_EQ(make_bound_pyramid(padded, 0).depth(), 0);
  EXPECT_THROW(make_bound_pyramid(padded, -1), Error);
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
      const BoundPyramid p = make_bound_pyramid(padded, 4);
      for (int level = 1; level <= 4; ++level) {
        const int side = 1 << level;
        for (int by = 0; by < h; ++by) {
          for (int bx = 0; bx < w; ++bx) {
            const double bound = block_bound(p, placed, level, bx, by);
            for (int y = by; y < std::min(h, by + side); ++y) {
              for (int x = bx; x < std::min(w, bx + side); ++x) {
                ASSERT_GE(bound, score(padded, placed, x, y))
                    << "case " << c << " level " << level << " block (" << bx << ", " << by
                    << ") pose (" << x << ", " << y << ")";
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

TEST(SearchBranchAndBound, EqualsExhaustiveOnRandomCases) {
  std::mt19937 rng(2025);
  int compared = 0;
  for (int c = 0; c < 400; ++c) {
    const int w = uniform_int(rng, 1, c % 10 == 0 ? 48 : 26);
    const int h = uniform_int(rng, 1, c % 10 == 0 ? 48 : 26);
    const auto kind = static_cast<GridKind>(c % static_cast<int>(GridKind::Count));
    const EvidenceGrid g = make_grid(rng, w, h, kind);
    const int headings = c % 4 == 0 ? 1 : uniform_int(rng, 1, 5);
    const int value_kind = uniform_int(rng, 0, 2);
    std::vector<SparseLocalGrid> locals;
    int extent = 0;
    for (int it = 0; it < headings; ++it) {
      const int n = c % 37 == 0 ? 0 : uniform_int(rng, 1, 48);
      locals.push_back(make_local(rng, n, uniform_int(rng, 0, 10), value_kind));
      extent = std::max(extent, locals.back().extent());
    }
    const Lattice lat = make_lattice(rng, w, h, headings);
    const int depth = uniform_int(rng, 0, bound_depth_for(lat) + 1);
    for (ArcRule rule : kRules) {
      const PaddedGrid padded = pad_grid(g, extent + uniform_int(rng, 0, 2), rule);
      const BoundPyramid pyramid = make_bound_pyramid(padded, depth);
      const std::string what = "case " + std::to_string(c) + " rule " +
                               std::to_string(static_cast<int>(rule)) + " depth " +
                               std::to_string(depth);
      SearchLevel level = level_of(padded, locals);
      level.threads = c % 3 == 0 ? 2 : 1;  // results never depend on it
      expect_same_as_exhaustive(lat, level, pyramid, what);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 800);
}

TEST(SearchBranchAndBound, ExclusionGivesTheBestPoseOutsideIt) {
  std::mt19937 rng(77);
  for (int c = 0; c < 200; ++c) {
    const int w = uniform_int(rng, 2, 30), h = uniform_int(rng, 2, 30);
    const EvidenceGrid g =
        make_grid(rng, w, h, static_cast<GridKind>(c % static_cast<int>(GridKind::Count)));
    const int headings = uniform_int(rng, 1, 5);
    std::vector<SparseLocalGrid> locals;
    int extent = 0;
    for (int it = 0; it < headings; ++it) {
      locals.push_back(make_local(rng, uniform_int(rng, 1, 40), uniform_int(rng, 0, 8), 1));
      extent = std::max(extent, locals.back().extent());
    }
    const Lattice lat = make_lattice(rng, w, h, headings);
    const PaddedGrid padded = pad_grid(g, extent, ArcRule::Neutral);
    const BoundPyramid pyramid = make_bound_pyramid(padded, bound_depth_for(lat));
    const SearchLevel level = level_of(padded, locals);
    const SearchResult all = search_exhaustive(lat, level);
    const Exclusion ex{all.best, uniform_int(rng, 0, 6) + 0.5, uniform_int(rng, 0, 2)};
    // The oracle: the exhaustive best among poses outside the exclusion.
    std::optional<LatticePose> expected;
    for (const auto& p : all.scored) {
      if (ex.contains(p.ix, p.iy, p.it)) continue;
      if (!expected || p.score > expected->score) expected = p;  // scan order = index order
    }
    const SearchResult b = search_branch_and_bound(lat, level, pyramid, ex);
    if (!expected) {
      EXPECT_EQ(b.poses_scored, 0) << c;
      continue;
    }
    ASSERT_GT(b.poses_scored, 0) << c;
    EXPECT_EQ(b.best.ix, expected->ix) << c;
    EXPECT_EQ(b.best.iy, expected->iy) << c;
    EXPECT_EQ(b.best.it, expected->it) << c;
    EXPECT_EQ(b.best.score, expected->score) << c;
    for (const auto& p : b.scored) EXPECT_FALSE(ex.contains(p.ix, p.iy, p.it)) << c;
  }
}

TEST(SearchBranchAndBound, AllZeroGridGoesToTheFirstPoseAndPrunesTheRest) {
  std::mt19937 rng(3);
  GridGeometry geo;
  geo.width = 40;
  geo.height = 30;
  const EvidenceGrid g(geo, 0.0f);
  std::vector<SparseLocalGrid> locals;
  for (int it = 0; it < 4; ++it) locals.push_back(make_local(rng, 30, 6, 1));
  Lattice lat;
  lat.x0 = 5, lat.x1 = 39, lat.y0 = 2, lat.y1 = 29;  // clipped at the right and top edges
  lat.headings = 4;
  lat.step_theta = 1.0;
  for (ArcRule rule : kRules) {
    const PaddedGrid padded = pad_grid(g, 6, rule);
    const SearchResult r = expect_same_as_exhaustive(lat, level_of(padded, locals),
                                                     make_bound_pyramid(padded, 6), "zero grid");
    EXPECT_EQ(r.best.ix, 5);
    EXPECT_EQ(r.best.iy, 2);
    EXPECT_EQ(r.best.it, 0);
    EXPECT_EQ(r.best.score, 0.0);
    // Every bound equals the first pose's score; only blocks holding a lower index are opened.
    EXPECT_LE(r.poses_scored, 4);
  }
}

TEST(SearchBranchAndBound, ConstantGridTiesGoToTheLowestIndex) {
  GridGeometry geo;
  geo.width = 20;
  geo.height = 20;
  const EvidenceGrid g(geo, 1.0f);
  SparseLocalGrid l;  // the same grid for every heading: every pose scores alike
  l.dx = {-1, 0, 2, 1};
  l.dy = {-2, 0, 0, 3};
  l.value = {0.25f, 1.0f, 0.5f, 1.0f / 3.0f};
  const std::vector<SparseLocalGrid> locals(3, l);
  Lattice lat;
  lat.x0 = 3, lat.x1 = 16, lat.y0 = 3, lat.y1 = 16;
  lat.headings = 3;
  lat.step_theta = 1.0;
  for (ArcRule rule : kRules) {
    const PaddedGrid padded = pad_grid(g, 3, rule);
    const SearchResult r = expect_same_as_exhaustive(lat, level_of(padded, locals),
                                                     make_bound_pyramid(padded, 4), "constant");
    EXPECT_EQ(r.best.ix, 3);
    EXPECT_EQ(r.best.iy, 3);
    EXPECT_EQ(r.best.it, 0);
  }
}

TEST(SearchBranchAndBound, RepeatedPeaksGoToTheLowestIndex) {
  // +1 every 5 cells in x and 3 in y; a one-cell local grid scores 1 on each of them. The
  // lowest (it, iy, ix) peak is on heading 1 (heading 0 scores nothing).
  GridGeometry geo;
  geo.width = 33;
  geo.height = 27;
  EvidenceGrid g(geo, 0.0f);
  for (int y = 1; y < 27; y += 3) {
    for (int x = 2; x < 33; x += 5) g.at(x, y) = 1.0f;
  }
  SparseLocalGrid none, one;
  one.dx = {0};
  one.dy = {0};
  one.value = {1.0f};
  const std::vector<SparseLocalGrid> locals = {none, one, one};
  Lattice lat;
  lat.x0 = 4, lat.x1 = 32, lat.y0 = 5, lat.y1 = 26;
  lat.headings = 3;
  lat.step_theta = 1.0;
  for (int depth = 0; depth <= 6; ++depth) {
    const PaddedGrid padded = pad_grid(g, 1);
    const SearchResult r =
        expect_same_as_exhaustive(lat, level_of(padded, locals), make_bound_pyramid(padded, depth),
                                  "peaks depth " + std::to_string(depth));
    EXPECT_EQ(r.best.ix, 7);
    EXPECT_EQ(r.best.iy, 7);
    EXPECT_EQ(r.best.it, 1);
    EXPECT_EQ(r.best.score, 1.0);
  }
}

TEST(SearchBranchAndBound, ScoresFewPosesOnAStructuredMap) {
  // Rooms: +1 contours around free (-1) interiors. Each heading's local grid is a patch of
  // the map around a true pose (with cells dropped), so one pose clearly wins.
  std::mt19937 rng(99);
  GridGeometry geo;
  geo.width = 96;
  geo.height = 96;
  EvidenceGrid g(geo, 0.0f);
  for (int r = 0; r < 12; ++r) {
    const int x0 = uniform_int(rng, 2, 70), y0 = uniform_int(rng, 2, 70);
    const int x1 = x0 + uniform_int(rng, 5, 22), y1 = y0 + uniform_int(rng, 5, 22);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const bool edge = x == x0 || x == x1 || y == y0 || y == y1;
        if (edge) {
          g.at(x, y) = 1.0f;
        } else if (g.at(x, y) == 0.0f) {
          g.at(x, y) = -1.0f;
        }
      }
    }
  }
  const int tx = 40, ty = 45;
  std::vector<SparseLocalGrid> locals;
  for (int it = 0; it < 6; ++it) {
    SparseLocalGrid l;
    for (int dy = -10; dy <= 10; ++dy) {
      for (int dx = -10; dx <= 10; ++dx) {
        const float v = g.at(tx + dx, ty + dy);
        if (v == 0.0f || uniform_int(rng, 0, 9) < 3 + it) continue;
        l.dx.push_back(dx);
        l.dy.push_back(dy);
        l.value.push_back(v > 0.0f ? 0.1f : -0.02f);
      }
    }
    locals.push_back(l);
  }
  Lattice lat;
  lat.x0 = 20, lat.x1 = 60, lat.y0 = 25, lat.y1 = 65;  // 41 x 41
  lat.headings = 6;
  lat.step_theta = 1.0;
  for (ArcRule rule : kRules) {
    const PaddedGrid padded = pad_grid(g, 10, rule);
    const SearchResult r = expect_same_as_exhaustive(
        lat, level_of(padded, locals), make_bound_pyramid(padded, bound_depth_for(lat)), "rooms");
    EXPECT_EQ(r.best.ix, tx);
    EXPECT_EQ(r.best.iy, ty);
    EXPECT_LT(r.poses_scored, 41 * 41 * 6 / 4);
  }
}

TEST(SearchBranchAndBound, RejectsBadInput) {
  GridGeometry geo;
  geo.width = 10;
  geo.height = 8;
  const EvidenceGrid g(geo, 0.0f);
  const PaddedGrid padded = pad_grid(g, 2);
  const BoundPyramid pyramid = make_bound_pyramid(padded, 2);
  SparseLocalGrid l;
  l.dx = {0, 2};
  l.dy = {0, -1};
  l.value = {1.0f, -1.0f};
  const std::vector<SparseLocalGrid> locals = {l};
  Lattice lat;
  lat.x0 = 0, lat.x1 = 9, lat.y0 = 0, lat.y1 = 7;
  EXPECT_NO_THROW(search_branch_and_bound(lat, level_of(padded, locals), pyramid));

  auto expect_error = [&](const Lattice& la, const SearchLevel& level, const BoundPyramid& p,
                          const std::string& text) {
    try {
      search_branch_and_bound(la, level, p);
      ADD_FAILURE() << "no error, expected: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  Lattice outside = lat;
  outside.x1 = 10;
  expect_error(outside, level_of(padded, locals), pyramid, "inside the 10 x 8 map");
  Lattice empty = lat;
  empty.y0 = 5, empty.y1 = 4;
  expect_error(empty, level_of(padded, locals), pyramid, "must be non-empty");
  Lattice no_headings = lat;
  no_headings.headings = 0;
  expect_error(no_headings, level_of(padded, locals), pyramid, "headings = 0");
  const PaddedGrid other = pad_grid(g, 3);
  expect_error(lat, level_of(other, locals), pyramid, "was not built from the searched grid");
  SparseLocalGrid wide = l;
  wide.dx.push_back(3);
  wide.dy.push_back(0);
  wide.value.push_back(1.0f);
  const std::vector<SparseLocalGrid> wide_locals = {wide};
  expect_error(lat, level_of(padded, wide_locals), pyramid, "exceeds the padding 2");
}

// --- Rigid scan points: heading-interval bounds, exclusion, incumbent, budget, threads ------

/// Rooms like a thinned map: +1 one-cell contours around -1 interiors, unknown elsewhere.
EvidenceGrid make_rooms(std::mt19937& rng, int w, int h) {
  GridGeometry geo;
  geo.width = w;
  geo.height = h;
  EvidenceGrid g(geo, 0.0f);
  const int rooms = 1 + w * h / 150;
  for (int r = 0; r < rooms; ++r) {
    const int x0 = uniform_int(rng, 0, w - 1), y0 = uniform_int(rng, 0, h - 1);
    const int x1 = std::min(w - 1, x0 + uniform_int(rng, 2, 18));
    const int y1 = std::min(h - 1, y0 + uniform_int(rng, 2, 18));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if (x == x0 || x == x1 || y == y0 || y == y1) {
          g.at(x, y) = 1.0f;
        } else if (g.at(x, y) == 0.0f) {
          g.at(x, y) = -1.0f;
        }
      }
    }
  }
  return g;
}

/// The scan a robot at cell (tx, ty) + a sub-cell offset with heading theta sees on g (cells
/// of `res` m): each beam ends in the first cell > 0 it meets (a little noise), or has no
/// return when it meets none within the max range or leaves the map.
RangeScan scan_from(std::mt19937& rng, const EvidenceGrid& g, double res, int tx, int ty,
                    double theta, int beams, double max_range) {
  RangeScan scan;
  scan.max_range = max_range;
  const double x0 = tx + uniform_real(rng, -0.5, 0.5), y0 = ty + uniform_real(rng, -0.5, 0.5);
  const double a0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
  for (int k = 0; k < beams; ++k) {
    const double a = a0 + 2.0 * std::numbers::pi * k / beams;
    double range = max_range;
    for (double d = 0.0; d * res < max_range; d += 0.25) {
      const int x = static_cast<int>(std::floor(x0 + d * std::cos(theta + a) + 0.5));
      const int y = static_cast<int>(std::floor(y0 + d * std::sin(theta + a) + 0.5));
      if (!g.geometry.contains(x, y)) break;
      if (g.at(x, y) > 0.0f) {
        range = std::max(0.0, d * res + uniform_real(rng, -0.3, 0.3) * res);
        break;
      }
    }
    scan.angles.push_back(a);
    scan.ranges.push_back(range);
  }
  if (std::none_of(scan.ranges.begin(), scan.ranges.end(),
                   [&](double r) { return r < max_range; })) {
    scan.ranges[0] = 0.5 * max_range;
  }
  return scan;
}

/// A level whose local grids are the rigid points rasterized, as the estimator makes it.
SearchLevel points_level(const PaddedGrid& padded, const ScanPoints& points) {
  const double res = padded.grid.geometry.resolution;
  SearchLevel level{&padded, [&points, res](double theta, const Eigen::Vector2d& centre) {
                      return rasterize_points(points, theta, res, centre);
                    }};
  level.points = &points;
  return level;
}

/// One random search problem over rigid scan points.
struct ScanCase {
  EvidenceGrid grid;
  RangeScan scan;
  ScanPoints points;
  Lattice lat;
  int depth = 0;
  int pad = 0;
  ArcRule rule = ArcRule::Neutral;
  std::string what;
};

ScanCase make_scan_case(std::mt19937& rng, int c) {
  ScanCase s;
  const double res = c % 2 == 0 ? 0.05 : 0.1;
  const int w = uniform_int(rng, 1, c % 8 == 0 ? 48 : 28);
  const int h = uniform_int(rng, 1, c % 8 == 0 ? 48 : 28);
  const int kind = c % 8;
  switch (kind) {
    case 0:
    case 1:
      s.grid = make_grid(rng, w, h, GridKind::Sparse);
      break;
    case 2:
    case 3:
      s.grid = make_rooms(rng, w, h);
      break;
    case 4:
      s.grid = make_grid(rng, w, h, c % 3 == 0 ? GridKind::Zero : GridKind::Ternary);
      break;
    case 5:
      s.grid = make_grid(rng, w, h, GridKind::Periodic);
      break;
    case 6:  // not ternary: the float bound levels
      s.grid = make_grid(rng, w, h, c % 2 == 0 ? GridKind::Floats : GridKind::Constant);
      break;
    default: {  // needles: a few occupied cells in unknown space. With few points, a bound
                // is tight: one that misses where a point can land prunes the winner.
      GridGeometry geo;
      geo.width = w;
      geo.height = h;
      s.grid = EvidenceGrid(geo, 0.0f);
      for (int k = uniform_int(rng, 1, 3); k > 0; --k) {
        s.grid.at(uniform_int(rng, 0, w - 1), uniform_int(rng, 0, h - 1)) = 1.0f;
      }
      break;
    }
  }
  s.grid.geometry.resolution = res;
  const int beams = uniform_int(rng, 1, kind == 7 ? 3 : 40);
  const double max_range = uniform_real(rng, 0.15, c % 5 == 0 || kind == 7 ? 2.5 : 1.2);
  if (kind == 3) {  // seen from a pose of the map: one clear peak, deep pruning
    s.scan = scan_from(rng, s.grid, res, uniform_int(rng, 0, w - 1), uniform_int(rng, 0, h - 1),
                       uniform_real(rng, -3.0, 3.0), beams, max_range);
  } else {
    s.scan = random_scan(rng, beams, max_range);
  }
  const ScanModelOptions model = c % 3 == 2
                                     ? ScanModelOptions{ScanModel::Hits, 1}
                                     : ScanModelOptions{ScanModel::Samples, uniform_int(rng, 1, 5)};
  s.points = scan_points(s.scan, model);
  const int headings = c % 10 == 0 ? 1 : uniform_int(rng, 2, 40);
  s.lat = make_lattice(rng, w, h, headings);
  s.lat.theta0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
  s.lat.step_theta = std::exp(uniform_real(rng, std::log(0.01), std::log(0.5)));
  if (c % 9 == 4) s.lat.step_theta = -s.lat.step_theta;
  s.depth = uniform_int(rng, 0, 8);
  s.pad = static_cast<int>(std::ceil(s.points.max_norm / res)) + uniform_int(rng, 3, 5);
  s.rule = (c / 2) % 2 == 0 ? ArcRule::Neutral : ArcRule::Signed;
  std::ostringstream what;
  what << "case " << c << ": map " << w << " x " << h << " res " << res << " kind " << kind << ", "
       << beams << " beams (" << s.points.hit_count << " ends, " << s.points.size()
       << " points, max_norm " << s.points.max_norm << "), lattice x [" << s.lat.x0 << ", "
       << s.lat.x1 << "] y [" << s.lat.y0 << ", " << s.lat.y1 << "] " << headings
       << " headings step " << s.lat.step_theta << ", depth " << s.depth << ", pad " << s.pad
       << ", rule " << static_cast<int>(s.rule);
  s.what = what.str();
  return s;
}

/// Index of a lattice pose in search_exhaustive's `scored` (heading, row, column order).
std::size_t lattice_index(const Lattice& lat, int ix, int iy, int it) {
  const auto nx = static_cast<std::size_t>(lat.x1 - lat.x0 + 1);
  const auto ny = static_cast<std::size_t>(lat.y1 - lat.y0 + 1);
  return (static_cast<std::size_t>(it) * ny + static_cast<std::size_t>(iy - lat.y0)) * nx +
         static_cast<std::size_t>(ix - lat.x0);
}

bool in_lattice(const Lattice& lat, const LatticePose& p) {
  return p.ix >= lat.x0 && p.ix <= lat.x1 && p.iy >= lat.y0 && p.iy <= lat.y1 && p.it >= 0 &&
         p.it < lat.headings;
}

void expect_pose(const LatticePose& got, const LatticePose& want, const std::string& what) {
  EXPECT_EQ(got.ix, want.ix) << what;
  EXPECT_EQ(got.iy, want.iy) << what;
  EXPECT_EQ(got.it, want.it) << what;
  EXPECT_EQ(got.score, want.score) << what;
}

/// The leaves a search scored are lattice poses with their exhaustive scores, each once.
void expect_leaves_exact(const SearchResult& r, const SearchResult& exhaustive, const Lattice& lat,
                         const std::string& what) {
  EXPECT_EQ(r.poses_scored, static_cast<long long>(r.scored.size())) << what;
  std::vector<char> seen(exhaustive.scored.size(), 0);
  for (const auto& p : r.scored) {
    ASSERT_TRUE(in_lattice(lat, p)) << what;
    const std::size_t k = lattice_index(lat, p.ix, p.iy, p.it);
    ASSERT_LT(k, exhaustive.scored.size()) << what;
    EXPECT_EQ(p.score, exhaustive.scored[k].score) << what;
    EXPECT_FALSE(seen[k]) << what << ": pose scored twice";
    seen[k] = 1;
  }
}

/// Checks an unbudgeted search result against the exhaustive best.
void expect_exact(const SearchResult& r, const SearchResult& e, const Lattice& lat,
                  const std::string& what) {
  expect_pose(r.best, e.best, what);
  EXPECT_TRUE(r.proven_optimal) << what;
  EXPECT_EQ(r.upper_bound, r.best.score) << what;
  expect_leaves_exact(r, e, lat, what);
}

/// The exhaustive best outside `ex`, from exhaustive's scored poses (in index order).
std::optional<LatticePose> best_outside(const SearchResult& e, const Exclusion& ex) {
  std::optional<LatticePose> best;
  for (const auto& p : e.scored) {
    if (ex.contains(p.ix, p.iy, p.it)) continue;
    if (!best || p.score > best->score) best = p;
  }
  return best;
}

TEST(SearchBranchAndBound, HeadingIntervalsEqualExhaustiveOnRandomScans) {
  std::mt19937 rng(5150);
  int compared = 0, deep = 0, intervals_ran = 0;
  for (int c = 0; c < 320; ++c) {
    const ScanCase s = make_scan_case(rng, c);
    const PaddedGrid padded = pad_grid(s.grid, s.pad, s.rule);
    const BoundPyramid pyramid = make_bound_pyramid(padded, s.depth);
    const SearchLevel level = points_level(padded, s.points);
    const SearchResult e = search_exhaustive(s.lat, level);
    const HeadingGrids grids(s.lat, level);  // shared by the searches below

    BranchAndBoundOptions intervals;
    intervals.heading_intervals = true;
    const SearchResult a = search_branch_and_bound(s.lat, grids, pyramid, intervals);
    expect_exact(a, e, s.lat, s.what + " [intervals]");
    deep += a.poses_scored * 4 < e.poses_scored ? 1 : 0;

    const SearchResult b = search_branch_and_bound(s.lat, grids, pyramid, {});
    expect_exact(b, e, s.lat, s.what + " [no intervals]");
    // Interval bounds count points, not local cells: the counters differ when they ran.
    intervals_ran += a.cells_scored != b.cells_scored ? 1 : 0;

    // Two threads on one shared queue, with heading grids built lazily by both.
    const HeadingGrids fresh(s.lat, level);
    BranchAndBoundOptions two = intervals;
    two.heading_intervals = c % 2 == 0;
    two.threads = 2;
    expect_exact(search_branch_and_bound(s.lat, fresh, pyramid, two), e, s.lat,
                 s.what + " [2 threads]");
    ++compared;
  }
  EXPECT_EQ(compared, 320);
  EXPECT_GT(deep, 20);  // the bounds prune in a fair share of the cases
}

/// The best pose of `window` (a sub-rectangle of the translations of `all`, same headings),
/// from an exhaustive search over `all`: a pose's score does not depend on the lattice.
LatticePose best_in_window(const SearchResult& all, const Lattice& window) {
  std::optional<LatticePose> best;
  for (const auto& p : all.scored) {  // index order: the first of equal scores wins
    if (!in_lattice(window, p)) continue;
    if (!best || p.score > best->score) best = p;
  }
  return *best;
}

/// One or two beam ends over a map of a few occupied cells: every bound is then the number of
/// occupied cells its pooled window catches, so a window that misses a cell where a point can
/// land (a widening or a pooled level too small) prunes the winner. Each case searches many
/// sub-windows of the map (blocks aligned differently, other winners) on shared heading grids.
TEST(SearchBranchAndBound, HeadingIntervalsFindIsolatedOccupiedCells) {
  std::mt19937 rng(1701);
  int found = 0, searches = 0;
  for (int c = 0; c < 240; ++c) {
    const double res = c % 3 == 0 ? 0.1 : 0.05;
    const int w = uniform_int(rng, 8, 32), h = uniform_int(rng, 8, 32);
    GridGeometry geo;
    geo.width = w;
    geo.height = h;
    geo.resolution = res;
    EvidenceGrid g(geo, 0.0f);
    for (int k = uniform_int(rng, 1, 2); k > 0; --k) {
      g.at(uniform_int(rng, 0, w - 1), uniform_int(rng, 0, h - 1)) = 1.0f;
    }
    RangeScan scan;
    scan.max_range = 3.0;
    for (int k = uniform_int(rng, 1, 2); k > 0; --k) {
      scan.angles.push_back(uniform_real(rng, -std::numbers::pi, std::numbers::pi));
      scan.ranges.push_back(uniform_real(rng, 0.3, 2.5));
    }
    const ScanPoints points = scan_points(scan, c % 4 == 0 ? ScanModelOptions{ScanModel::Samples, 2}
                                                           : ScanModelOptions{ScanModel::Hits, 1});
    Lattice all;
    all.x0 = 0, all.x1 = w - 1, all.y0 = 0, all.y1 = h - 1;
    all.headings = uniform_int(rng, 8, 48);
    all.theta0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
    all.step_theta = std::exp(uniform_real(rng, std::log(0.005), std::log(0.15)));
    const PaddedGrid padded =
        pad_grid(g, static_cast<int>(std::ceil(points.max_norm / res)) + 3, ArcRule::Neutral);
    const BoundPyramid pyramid = make_bound_pyramid(padded, uniform_int(rng, 2, 8));
    const SearchLevel level = points_level(padded, points);
    const SearchResult e = search_exhaustive(all, level);
    const HeadingGrids grids(all, level);
    found += e.best.score > 0.0 ? 1 : 0;
    for (int k = 0; k < 2; ++k) {
      Lattice window = all;
      if (k > 0) {
        const Lattice r = make_lattice(rng, w, h, all.headings);
        window.x0 = r.x0, window.x1 = r.x1, window.y0 = r.y0, window.y1 = r.y1;
      }
      BranchAndBoundOptions o;
      o.heading_intervals = true;
      o.threads = c % 4 == 1 ? 2 : 1;
      const SearchResult b = search_branch_and_bound(window, grids, pyramid, o);
      const std::string what = "needles case " + std::to_string(c) + " window " +
                               std::to_string(k) + " map " + std::to_string(w) + " x " +
                               std::to_string(h) + " step " + std::to_string(all.step_theta);
      expect_pose(b.best, best_in_window(e, window), what);
      EXPECT_TRUE(b.proven_optimal) << what;
      for (const auto& p : b.scored) EXPECT_TRUE(in_lattice(window, p)) << what;
      expect_leaves_exact(b, e, all, what);
      ++searches;
    }
  }
  EXPECT_EQ(searches, 240 * 2);
  EXPECT_GT(found, 30);  // many cases have a pose that lands a point on an occupied cell
}

TEST(SearchBranchAndBound, ExclusionAndIncumbentWithHeadingIntervals) {
  std::mt19937 rng(6502);
  int excluded_all = 0;
  for (int c = 0; c < 240; ++c) {
    const ScanCase s = make_scan_case(rng, c);
    const PaddedGrid padded = pad_grid(s.grid, s.pad, s.rule);
    const BoundPyramid pyramid = make_bound_pyramid(padded, s.depth);
    const SearchLevel level = points_level(padded, s.points);
    const SearchResult e = search_exhaustive(s.lat, level);
    const HeadingGrids grids(s.lat, level);
    auto random_pose = [&] {
      return e.scored[static_cast<std::size_t>(
          uniform_int(rng, 0, static_cast<int>(e.scored.size()) - 1))];
    };

    // Exclusion around the winner or any pose: the best pose outside it.
    const LatticePose center = c % 2 == 0 ? e.best : random_pose();
    const Exclusion ex{center, uniform_int(rng, 0, 6) + (c % 3 == 0 ? 0.0 : 0.5),
                       uniform_int(rng, 0, 3)};
    const std::optional<LatticePose> outside = best_outside(e, ex);
    for (int threads : {1, 2}) {
      BranchAndBoundOptions o;
      o.exclude = {ex};
      o.heading_intervals = (c + threads) % 2 == 0 || threads == 1;
      o.threads = threads;
      const std::string what = s.what + " [exclusion, " + std::to_string(threads) + " threads]";
      const SearchResult r = search_branch_and_bound(s.lat, grids, pyramid, o);
      for (const auto& p : r.scored) EXPECT_FALSE(ex.contains(p.ix, p.iy, p.it)) << what;
      expect_leaves_exact(r, e, s.lat, what);
      if (!outside) {
        EXPECT_EQ(r.poses_scored, 0) << what;
        excluded_all += threads == 1;
        continue;
      }
      expect_pose(r.best, *outside, what);
      EXPECT_TRUE(r.proven_optimal) << what;
    }

    // An incumbent that is a real scored pose: the exhaustive best beats or ties it at a
    // lower index, so the result is still the exhaustive best.
    {
      BranchAndBoundOptions o;
      o.heading_intervals = c % 4 != 1;
      o.incumbent = c % 5 == 0 ? e.best : random_pose();
      const std::string what = s.what + " [incumbent]";
      const SearchResult r = search_branch_and_bound(s.lat, grids, pyramid, o);
      expect_pose(r.best, e.best, what);
      EXPECT_TRUE(r.proven_optimal) << what;
      expect_leaves_exact(r, e, s.lat, what);
    }
    // Both, as the estimator's second-peak search uses them: incumbent outside the exclusion.
    if (outside) {
      std::vector<LatticePose> candidates;
      for (const auto& p : e.scored) {
        if (!ex.contains(p.ix, p.iy, p.it)) candidates.push_back(p);
      }
      BranchAndBoundOptions o;
      o.exclude = {ex};
      o.heading_intervals = true;
      o.incumbent = candidates[static_cast<std::size_t>(
          uniform_int(rng, 0, static_cast<int>(candidates.size()) - 1))];
      const std::string what = s.what + " [exclusion + incumbent]";
      const SearchResult r = search_branch_and_bound(s.lat, grids, pyramid, o);
      expect_pose(r.best, *outside, what);
      for (const auto& p : r.scored) EXPECT_FALSE(ex.contains(p.ix, p.iy, p.it)) << what;
    }
    // An incumbent nothing beats (scoring above every pose) is the result.
    {
      BranchAndBoundOptions o;
      o.heading_intervals = c % 2 == 0;
      LatticePose top = random_pose();
      top.score = e.best.score + 1.0;
      o.incumbent = top;
      const std::string what = s.what + " [unbeaten incumbent]";
      const SearchResult r = search_branch_and_bound(s.lat, grids, pyramid, o);
      expect_pose(r.best, top, what);
      EXPECT_TRUE(r.proven_optimal) << what;
      EXPECT_EQ(r.upper_bound, top.score) << what;
      expect_leaves_exact(r, e, s.lat, what);
    }
  }
  EXPECT_GT(excluded_all, 0);  // some exclusions hold the whole lattice
}

TEST(SearchBranchAndBound, AnytimeBudgetReturnsAScoredPoseAndAValidUpperBound) {
  std::mt19937 rng(31337);
  int stopped = 0;
  for (int c = 0; c < 4; ++c) {
    const double res = 0.05;
    const int w = 64, h = 56;
    const EvidenceGrid grid = [&] {
      EvidenceGrid g = c % 2 == 0 ? make_rooms(rng, w, h) : make_grid(rng, w, h, GridKind::Sparse);
      g.geometry.resolution = res;
      return g;
    }();
    const RangeScan scan =
        c % 2 == 0 ? scan_from(rng, grid, res, 30, 25, 0.4, 40, 2.5) : random_scan(rng, 40, 2.5);
    const ScanPoints points = scan_points(scan, c < 2 ? ScanModelOptions{ScanModel::Samples, 3}
                                                      : ScanModelOptions{ScanModel::Hits, 1});
    Lattice lat;
    lat.x0 = 0, lat.x1 = w - 1, lat.y0 = 0, lat.y1 = h - 1;
    lat.headings = 36;
    lat.theta0 = -0.9;
    lat.step_theta = 0.05;
    const PaddedGrid padded =
        pad_grid(grid, static_cast<int>(std::ceil(points.max_norm / res)) + 3);
    const BoundPyramid pyramid = make_bound_pyramid(padded, bound_depth_for(lat));
    const SearchLevel level = points_level(padded, points);
    const SearchResult e = search_exhaustive(lat, level);
    const HeadingGrids grids(lat, level);
    for (double budget : {1e-9, 1e-3, 0.05, 0.5}) {
      for (int threads : {1, 2}) {
        for (bool intervals : {false, true}) {
          BranchAndBoundOptions o;
          o.budget_ms = budget;
          o.threads = threads;
          o.heading_intervals = intervals;
          const std::string what = "case " + std::to_string(c) + " budget " +
                                   std::to_string(budget) + " threads " + std::to_string(threads) +
                                   " intervals " + std::to_string(intervals);
          const SearchResult r = search_branch_and_bound(lat, grids, pyramid, o);
          ASSERT_GE(r.poses_scored, 1) << what;
          ASSERT_TRUE(in_lattice(lat, r.best)) << what;
          EXPECT_EQ(r.best.score,
                    e.scored[lattice_index(lat, r.best.ix, r.best.iy, r.best.it)].score)
              << what;
          EXPECT_GE(r.upper_bound, e.best.score) << what;
          EXPECT_GE(e.best.score, r.best.score) << what;
          expect_leaves_exact(r, e, lat, what);
          if (r.proven_optimal) {
            expect_pose(r.best, e.best, what + " (proven optimal)");
            EXPECT_EQ(r.upper_bound, r.best.score) << what;
          } else {
            ++stopped;
          }
        }
      }
    }
    // No budget, or one never reached: proven optimal, the exhaustive best.
    for (double budget : {0.0, 1e9}) {
      BranchAndBoundOptions o;
      o.budget_ms = budget;
      o.heading_intervals = c % 2 == 1;
      expect_exact(search_branch_and_bound(lat, grids, pyramid, o), e, lat,
                   "case " + std::to_string(c) + " budget " + std::to_string(budget));
    }
  }
  EXPECT_GT(stopped, 0);  // a 1e-9 ms budget is over before the first node is expanded
}

TEST(SearchBranchAndBound, HeadingGridsCheckThePaddingAndTheLattice) {
  GridGeometry geo;
  geo.width = 12;
  geo.height = 10;
  geo.resolution = 0.1;
  const EvidenceGrid g(geo, 0.0f);
  const RangeScan scan{{0.0, 2.0}, {2.0, 1.0}, 5.0};  // the farthest point at 2 m: 20 cells
  const ScanPoints points = scan_points(scan, {ScanModel::Samples, 2});
  ASSERT_DOUBLE_EQ(points.max_norm, 2.0);
  Lattice lat;
  lat.x0 = 0, lat.x1 = 11, lat.y0 = 0, lat.y1 = 9;
  lat.headings = 8;
  lat.step_theta = 0.2;
  for (int pad : {5, 19, 20}) {
    const PaddedGrid narrow = pad_grid(g, pad);
    test::expect_error([&] { HeadingGrids grids(lat, points_level(narrow, points)); },
                       {"beyond the padding"});
  }
  const PaddedGrid wide = pad_grid(g, 23);
  const SearchLevel level = points_level(wide, points);
  const HeadingGrids grids(lat, level);
  const BoundPyramid pyramid = make_bound_pyramid(wide, 3);
  BranchAndBoundOptions o;
  o.heading_intervals = true;
  expect_exact(search_branch_and_bound(lat, grids, pyramid, o), search_exhaustive(lat, level), lat,
               "zero grid");
  Lattice other = lat;
  other.step_theta = 0.1;
  test::expect_error([&] { (void)search_branch_and_bound(other, grids, pyramid, o); },
                     {"another lattice"});
  SearchLevel none = level;
  none.global = nullptr;
  test::expect_error([&] { HeadingGrids bad(lat, none); }, {"no grid"});
}

}  // namespace
}  // namespace gridloc
