/// Seed 002's overlay on occupancy maps, timed on the apartment (maps/apartment_small.yaml,
/// 220 x 160 cells at 5 cm):
/// - BM_GridOverlay/<set>/<k>/<range>: make_grid_overlay with the first k hypotheses of a set
///   (0: "near", one pose and 9 others within 0.3 m and 0.1 rad of it, a large OI with internal
///   cells all round; 1: "spread", 10 free poses drawn over the whole map, a small OI), range
///   in metres (0: unlimited). Counters: oi, internal, useful cells.
/// - BM_GridInfo/<set>: grid_info at 200 points sampled in OI (10 hypotheses, 4 m), one point
///   per iteration in turn (10 predicted 90-beam scans and their classes).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "gridloc/engine/disambiguation/grid_overlay.hpp"
#include "gridloc/engine/disambiguation/grid_views.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc::bench {
namespace {

const OccupancyMap& apartment() {
  static const OccupancyMap map =
      load_ros_map(std::string(GRIDLOC_BENCH_MAPS_DIR) + "/apartment_small.yaml");
  return map;
}

bool free_at(const OccupancyMap& map, double x, double y) {
  const GridGeometry& g = map.geometry;
  const Cell c = g.cell_of(x - g.origin.x(), y - g.origin.y());
  return g.contains(c.ix, c.iy) && map.at(c.ix, c.iy) == CellState::Free;
}

/// Ten hypotheses: set 0 near one pose, set 1 spread over the map (seeded).
std::vector<Pose2> hypothesis_set(int set) {
  const OccupancyMap& map = apartment();
  Rng rng(5);
  const Pose2 base{2.03, 2.47, 0.61};
  std::vector<Pose2> poses;
  if (set == 0) poses.push_back(base);
  while (poses.size() < 10) {
    const Pose2 p =
        set == 0 ? Pose2{base.x + rng.uniform(-0.3, 0.3), base.y + rng.uniform(-0.3, 0.3),
                         base.theta + rng.uniform(-0.1, 0.1)}
                 : Pose2{rng.uniform(0.0, 10.0), rng.uniform(0.0, 7.0), rng.uniform(-3.14, 3.14)};
    if (free_at(map, p.x, p.y)) poses.push_back(p);
  }
  return poses;
}

double range_of(std::int64_t metres) {
  return metres == 0 ? std::numeric_limits<double>::infinity() : static_cast<double>(metres);
}

void BM_GridOverlay(benchmark::State& state) {
  std::vector<Pose2> hypotheses = hypothesis_set(static_cast<int>(state.range(0)));
  hypotheses.resize(static_cast<std::size_t>(state.range(1)));
  const double range = range_of(state.range(2));
  GridOverlay overlay;
  for (auto _ : state) {
    overlay = make_grid_overlay(apartment(), hypotheses, range);
    benchmark::DoNotOptimize(overlay.useful_count);
  }
  state.counters["oi"] = overlay.oi_count;
  state.counters["internal"] = overlay.internal_count;
  state.counters["useful"] = overlay.useful_count;
}
BENCHMARK(BM_GridOverlay)->ArgsProduct({{0, 1}, {2, 10}, {2, 4, 0}})->Unit(benchmark::kMillisecond);

void BM_GridInfo(benchmark::State& state) {
  const std::vector<Pose2> hypotheses = hypothesis_set(static_cast<int>(state.range(0)));
  const GridOverlay overlay = make_grid_overlay(apartment(), hypotheses, 4.0);
  Rng rng(1);
  const std::vector<Eigen::Vector2d> points = sample_overlay_cells(overlay, false, 200, rng);
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(grid_info(apartment(), hypotheses, points[next], 4.0));
    next = (next + 1) % points.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GridInfo)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gridloc::bench
