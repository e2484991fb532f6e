// Tests of branch and bound over rigid scan points (engine/src/correlation/branch_and_bound.cpp):
// heading-interval bounds and threads against search_exhaustive, exactly, on random scan cases
// and on isolated occupied cells, with exclusion zones and incumbents.
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
    // Two cases in three without min levels: free samples bound by the grid's minimum (and a
    // field's levels kept as int8 only).
    const BoundPyramid pyramid = make_bound_pyramid(
        padded, s.depth, c % 3 == 0 ? PyramidLevels::MaxAndMin : PyramidLevels::MaxOnly);
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

}  // namespace
}  // namespace gridloc
