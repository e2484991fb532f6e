// Tests of engine/src/correlation/memory.cpp and the correlation estimator's resource checks
// (issue 14): the estimate's terms, and grids, searches and Localizers over the limits
// refused before they are allocated.
#include "gridloc/engine/correlation/memory.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

/// A 100 x 80 walled room at 5 cm (5 x 4 m).
OccupancyMap room() {
  return test::walled_room(100, 80, 0.05, Eigen::Vector2d::Zero());
}

TEST(MemoryEstimate, GlobalGridSizeFollowsResampling) {
  const GridGeometry map = room().geometry;
  const GlobalGridSize same = global_grid_size(map, 0.05, 1.0);
  EXPECT_EQ(same.width, 100.0);
  EXPECT_EQ(same.height, 80.0);
  EXPECT_EQ(same.pad, 23.0);  // ceil(1 / 0.05) + 3
  const GlobalGridSize coarse = global_grid_size(map, 0.3, 0.0);
  EXPECT_EQ(coarse.width, 17.0);  // ceil(5 / 0.3)
  EXPECT_EQ(coarse.height, 14.0);
  // A tiny step is a number, not an int overflow: 5 m at 1 nm.
  EXPECT_EQ(global_grid_size(map, 1e-9, 0.0).width, 5e9);
  EXPECT_EQ(bound_pyramid_depth(same), 8);  // 2^7 = 128 >= 100, plus one
}

TEST(MemoryEstimate, TermsAreTheDocumentedBytesPerCell) {
  const GridGeometry map = room().geometry;
  CorrelationOptions options;
  options.resolution = 0.05;
  options.strategy = SearchStrategy::Exhaustive;
  const double padded = (100.0 + 46.0) * (80.0 + 46.0);
  // The map (1 B), the padded grid (int8 and floats: 10 B) and the unpadded build (6 B).
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0), 8000.0 + 10.0 * padded + 6.0 * 8000.0);
  // A laser's hits alone: the int8 cells alone, 2 B.
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0, {}, true),
            8000.0 + 2.0 * padded + 6.0 * 8000.0);
  // + 8 levels of 2 B (int8 only) and 1 B, pooling in two float working grids 8 B
  options.strategy = SearchStrategy::BranchAndBound;
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0),
            8000.0 + 10.0 * padded + (2.0 * 8 + 1.0) * padded + std::max(6.0 * 8000, 8.0 * padded));
  // A likelihood field's levels may keep their floats (10 B each).
  options.global = GlobalModel::LikelihoodField;
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0),
            8000.0 + 10.0 * padded + (10.0 * 8 + 1.0) * padded +
                std::max((6.0 + 8.0) * 8000, 8.0 * padded));
  // A laser's hits alone on it: int8 cells (2 B) and max-pooled int8 levels (1 B each, 1 B
  // for the minimum), pooled from copies (2 B).
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0, {}, true),
            8000.0 + 2.0 * padded + (1.0 * 8 + 1.0) * padded +
                std::max((6.0 + 8.0) * 8000, 2.0 * padded));
  // A pyramid capped at 3 levels counts 3 (CorrelationOptions::max_bound_depth).
  options.max_bound_depth = 3;
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0, {}, true),
            8000.0 + 2.0 * padded + (1.0 * 3 + 1.0) * padded +
                std::max((6.0 + 8.0) * 8000, 2.0 * padded));
  options.global = CorrelationOptions{}.global;
  const double grids = correlation_memory_bytes(map, options, 1.0);
  SearchSize search;
  search.translations = 1000;
  search.headings = 72;
  search.local_cells = 500;
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0, search) - grids, 72 * (300.0 + 12 * 500));
  search.every_pose = true;
  EXPECT_EQ(correlation_memory_bytes(map, options, 1.0, search) - grids,
            72 * (300.0 + 12 * 500) + 32.0 * 72 * 1000);
}

// The estimate covers what the estimator keeps: its padded grid, measured from its vectors.
TEST(MemoryEstimate, CoversTheGridsBuilt) {
  CorrelationOptions options;
  options.resolution = 0.05;
  options.strategy = SearchStrategy::Exhaustive;
  const CorrelationEstimator estimator(room(), load_sonar_ring(test::ring_path()), options);
  const PaddedGrid& g = estimator.level(0);
  const double kept = 4.0 * (g.grid.cells.size() + g.arc_cells.size()) +
                      static_cast<double>(g.grid8.size() + g.arc_cells8.size()) + 8000.0;
  const double estimate = correlation_memory_bytes(room().geometry, options,
                                                   load_sonar_ring(test::ring_path()).reach());
  EXPECT_GE(estimate, kept);
  EXPECT_LE(estimate, 1.5 * kept);
  // A laser's hits alone on a likelihood field: the int8 cells alone.
  options.global = GlobalModel::LikelihoodField;
  options.reach_m = 1.0;
  const CorrelationEstimator laser(room(), options);
  const PaddedGrid& h = laser.level(0);
  EXPECT_FALSE(h.has_floats());
  const double hits_kept = static_cast<double>(h.grid8.size() + h.arc_cells8.size()) + 8000.0;
  const double hits_estimate = correlation_memory_bytes(room().geometry, options, 1.0, {}, true);
  EXPECT_GE(hits_estimate, hits_kept);
  // and the transient build of the unpadded field (6 + 8 B a map cell)
  EXPECT_LE(hits_estimate, 1.5 * hits_kept + 14.0 * 8000.0);
}

// Issue 14: --step-xy 1e-4 on a 7.8 m room built a 78000 x 67000 grid (5 GB, then bad_alloc).
TEST(MemoryEstimate, AFineResolutionIsRefusedBeforeItIsBuilt) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  CorrelationOptions options;
  options.resolution = 1e-4;
  test::expect_error([&] { CorrelationEstimator(map, ring, options); },
                     {"global grid at 0.0001 m", "cells exceeds the limit", "--max-cells"});
  options.resolution = 0.004;  // the cells fit, the bound pyramid does not
  options.limits.max_memory_mb = 300;
  test::expect_error([&] { CorrelationEstimator(map, ring, options); },
                     {"map at 0.004 m", "MB, more than the limit of 300 MB", "--max-memory-mb"});
  options.resolution = 0.1;
  options.limits.max_memory_mb = 1;
  test::expect_error([&] { CorrelationEstimator(map, ring, options); }, {"--max-memory-mb"});
  options.limits.max_memory_mb = 0;
  test::expect_error([&] { CorrelationEstimator(map, ring, options); }, {"max_memory_mb"});
  options.limits = {};
  options.strategy = SearchStrategy::Multires;  // every level is checked
  options.limits.max_cells = 2000;  // the finest grid, 146 x 116, is over; coarser would fit
  test::expect_error([&] { CorrelationEstimator(map, ring, options); }, {"--max-cells"});
}

TEST(MemoryEstimate, ASearchOverTheLimitIsRefusedBeforeItRuns) {
  const OccupancyMap map = room();
  CorrelationOptions options;
  options.resolution = 0.05;
  options.reach_m = 2.0;
  options.limits.max_memory_mb = 64;  // the grids need about 3 MB, a global search a few more
  const CorrelationEstimator estimator(map, options);
  RangeScan scan;
  for (int k = 0; k < 360; ++k) {
    scan.angles.push_back(k * std::numbers::pi / 180.0);
    scan.ranges.push_back(1.5);
  }
  scan.max_range = 2.0;
  Observation observation;
  observation.scan = scan;
  SearchWindow window = estimator.global_window(observation);
  EXPECT_NO_THROW(estimator.estimate(observation, window));
  window.step_theta = 2.0 * std::numbers::pi / 90000;  // 90001 headings' local grids: ~0.9 GB
  test::expect_error([&] { estimator.estimate(observation, window); },
                     {"a search of 8000 cells x 90001 headings", "--max-memory-mb"});
  test::expect_error([&] { estimator.score_volume(observation, window); },
                     {"90001 headings", "--max-memory-mb"});
  window.step_theta = 1e-9;  // the heading count itself is capped
  test::expect_error([&] { estimator.estimate(observation, window); }, {"step_theta", "headings"});
  window.step_theta = 1e300;  // and a step is at most a turn
  test::expect_error([&] { estimator.estimate(observation, window); },
                     {"step_theta must lie in (0, 2 pi], got 1e+300"});
}

// Issue 14, case 4: the Localizer's estimator goes through the same estimate.
TEST(MemoryEstimate, TheLocalizersEstimatorIsChecked) {
  LocalizerOptions options;
  options.correlation.resolution = 0.05;
  options.correlation.limits.max_memory_mb = 1;
  test::expect_error([&] { Localizer(room(), LaserSensor{}, options); },
                     {"correlation estimator", "--max-memory-mb"});
  test::expect_error([&] { Localizer(room(), load_sonar_ring(test::ring_path()), options); },
                     {"--max-memory-mb"});
  options.correlation.limits = {};
  EXPECT_NO_THROW(Localizer(room(), LaserSensor{}, options));
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14, case 7: a resolution coarser than the map, or a 1 x 1 map, said "simulate: pose
// ... lies outside the map" though simulate never ran.
TEST(MemoryEstimate, AResolutionCoarserThanTheMapIsNamed) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  CorrelationOptions options;
  options.resolution = 1e3;
  test::expect_error([&] { CorrelationEstimator(room(), ring, options); },
                     {"resolution 1000 m", "coarser than the map (5 x 4 m)"});
  options.resolution = 0.1;
  const OccupancyMap one = test::walled_room(1, 1, 0.05, Eigen::Vector2d::Zero());
  test::expect_error([&] { CorrelationEstimator(one, ring, options); },
                     {"coarser than the map (0.05 x 0.05 m)"});
  // The last cell of a coarse grid overhangs the map: a winner there agrees with nothing,
  // it is not an error of a simulation nobody asked for.
  options.resolution = 3.0;  // 5 x 4 m: 2 x 2 cells, centres at 1.5 and 4.5 m (past 4 m)
  const CorrelationEstimator coarse(room(), ring, options);
  const std::vector<double> ranges(ring.sonars.size(), 1.0);
  SearchWindow window = coarse.global_window(Observation{ranges});
  EXPECT_NO_THROW(coarse.estimate(Observation{ranges}, window));
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14, case 5: --arc-depth 99999999999 crashed (SIGSEGV) drawing outside the canvas.
TEST(MemoryEstimate, AnArcDeeperThanTheCanvasIsRefused) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  CorrelationOptions options;
  for (double depth : {99999999999.0, 1e300, 2.5, -1.0}) {
    options.sonar.arc_depth_cells = depth;
    test::expect_error([&] { CorrelationEstimator(room(), ring, options); },
                       {"arc depth must lie in [0, 2] cells"});
  }
  options.sonar.arc_depth_cells = 2.0;
  EXPECT_NO_THROW(CorrelationEstimator(room(), ring, options));
}

}  // namespace
}  // namespace gridloc
