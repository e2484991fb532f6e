// Tests of the anytime branch-and-bound search (engine/src/correlation/branch_and_bound.cpp):
// a budget returns a scored pose and a valid upper bound, and the exact result when it suffices.
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

}  // namespace
}  // namespace gridloc
