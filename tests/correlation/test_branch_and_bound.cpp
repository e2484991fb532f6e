// Tests of the branch-and-bound search of engine/src/correlation/branch_and_bound.cpp on local
// grids: against search_exhaustive, exactly (pose and score bit for bit), on random grids,
// local grids and lattices with fixed seeds, on grids made of ties, with an exclusion zone;
// and its checks of bad input (heading grids of rigid points included).
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

#include "correlation/scan_cases.hpp"
#include "correlation/search_cases.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;  // the shared search cases, random draws and checks

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
      // Without min levels the negative cells bound by the grid's minimum: looser, as exact.
      for (PyramidLevels levels : {PyramidLevels::MaxAndMin, PyramidLevels::MaxOnly}) {
        const BoundPyramid pyramid = make_bound_pyramid(padded, depth, levels);
        const std::string what =
            "case " + std::to_string(c) + " rule " + std::to_string(static_cast<int>(rule)) +
            " depth " + std::to_string(depth) + " min levels " + std::to_string(pyramid.min_levels);
        SearchLevel level = level_of(padded, locals);
        level.threads = c % 3 == 0 ? 2 : 1;  // results never depend on it
        expect_same_as_exhaustive(lat, level, pyramid, what);
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 1600);
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

/// A random search case of ExclusionGivesTheBestPoseOutsideIt's kind, with its heading grids.
struct RandomSearch {
  EvidenceGrid grid;
  std::vector<SparseLocalGrid> locals;
  Lattice lattice;
  std::optional<PaddedGrid> padded;
  std::optional<BoundPyramid> pyramid;
  SearchLevel level() const { return level_of(*padded, locals); }
};

RandomSearch random_search(std::mt19937& rng, int c) {
  RandomSearch r;
  const int w = uniform_int(rng, 2, 30), h = uniform_int(rng, 2, 30);
  r.grid = make_grid(rng, w, h, static_cast<GridKind>(c % static_cast<int>(GridKind::Count)));
  const int headings = uniform_int(rng, 1, 5);
  int extent = 0;
  for (int it = 0; it < headings; ++it) {
    r.locals.push_back(make_local(rng, uniform_int(rng, 1, 40), uniform_int(rng, 0, 8), 1));
    extent = std::max(extent, r.locals.back().extent());
  }
  r.lattice = make_lattice(rng, w, h, headings);
  r.padded = pad_grid(r.grid, extent, ArcRule::Neutral);
  r.pyramid = make_bound_pyramid(*r.padded, bound_depth_for(r.lattice));
  return r;
}

/// Expects every pose of the exhaustive search `all` that scores options.keep_share of its
/// best (and lies outside options.keep_outside's neighbourhood of it) among b's scored
/// poses; returns how many there were.
int expect_share_scored(const SearchResult& b, const SearchResult& all,
                        const BranchAndBoundOptions& options, int c) {
  Exclusion around_best = options.keep_outside.value_or(Exclusion{});
  around_best.center = all.best;
  std::set<std::tuple<int, int, int>> scored;
  for (const LatticePose& p : b.scored) scored.insert({p.ix, p.iy, p.it});
  int kept = 0;
  for (const LatticePose& p : all.scored) {
    if (p.score < options.keep_share * all.best.score) continue;
    if (options.keep_outside && around_best.contains(p.ix, p.iy, p.it)) continue;
    EXPECT_TRUE(scored.count({p.ix, p.iy, p.it})) << c << ": a pose within the share unscored";
    ++kept;
  }
  return kept;
}

// keep_share, then with keep_outside too: the same winner, every pose within the share (outside
// the best's neighbourhood) scored, and fewer poses scored with the neighbourhood skipped.
TEST(SearchBranchAndBound, KeepShareScoresEveryPoseNearTheBestWithTheSameWinner) {
  std::mt19937 rng(91), zones(93);
  int kept = 0, kept_outside = 0;
  long long scored_without = 0, scored_with = 0;
  for (int c = 0; c < 200; ++c) {
    const RandomSearch r = random_search(rng, c);
    const SearchLevel level = r.level();
    const SearchResult all = search_exhaustive(r.lattice, level);
    BranchAndBoundOptions options;
    options.keep_share = c % 2 == 0 ? 0.8 : 0.5;
    options.threads = c % 3 == 0 ? 2 : 1;
    const HeadingGrids grids(r.lattice, level);
    const SearchResult b = search_branch_and_bound(r.lattice, grids, *r.pyramid, options);
    EXPECT_EQ(b.best.ix, all.best.ix) << c;
    EXPECT_EQ(b.best.iy, all.best.iy) << c;
    EXPECT_EQ(b.best.it, all.best.it) << c;
    EXPECT_EQ(b.best.score, all.best.score) << c;
    EXPECT_TRUE(b.proven_optimal) << c;
    scored_without += b.poses_scored;
    BranchAndBoundOptions outside = options;
    outside.keep_outside =
        Exclusion{{}, uniform_real(zones, 0.0, 6.0), uniform_int(zones, 0, 2), 0.0};
    const SearchResult o = search_branch_and_bound(r.lattice, grids, *r.pyramid, outside);
    scored_with += o.poses_scored;
    expect_pose(o.best, all.best, std::to_string(c));
    EXPECT_TRUE(o.proven_optimal) << c;
    if (all.best.score <= 0.0) continue;  // the share of a score <= 0 keeps nothing more
    kept += expect_share_scored(b, all, options, c);
    kept_outside += expect_share_scored(o, all, outside, c);
  }
  EXPECT_GT(kept, 200);
  EXPECT_GT(kept_outside, 100);
  EXPECT_LT(scored_with, scored_without);
}

TEST(SearchBranchAndBound, MinScoreFindsTheBestWhenItReachesItAndOnlyThen) {
  std::mt19937 rng(92);
  int above = 0, below = 0;
  for (int c = 0; c < 200; ++c) {
    const RandomSearch r = random_search(rng, c);
    const SearchLevel level = r.level();
    const SearchResult all = search_exhaustive(r.lattice, level);
    BranchAndBoundOptions options;
    options.min_score = all.best.score + (c % 2 == 0 ? -0.5 : 0.5);
    const HeadingGrids grids(r.lattice, level);
    const SearchResult b = search_branch_and_bound(r.lattice, grids, *r.pyramid, options);
    if (all.best.score >= options.min_score) {
      ++above;
      EXPECT_EQ(b.best.ix, all.best.ix) << c;
      EXPECT_EQ(b.best.iy, all.best.iy) << c;
      EXPECT_EQ(b.best.it, all.best.it) << c;
      EXPECT_EQ(b.best.score, all.best.score) << c;
      EXPECT_TRUE(b.found) << c;
    } else {
      ++below;
      EXPECT_TRUE(!b.found || b.best.score < options.min_score) << c;
    }
  }
  EXPECT_GT(above, 50);
  EXPECT_GT(below, 50);
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
