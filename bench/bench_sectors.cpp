/// Seed 000's visibility sectors, timed on the bundled polygon maps (maps/polygons/; the
/// office only with GRIDLOC_BENCH_FULL=1):
/// - BM_ComputeSectors/<map>: compute_sectors() with default options (5 cm sampling, labels
///   from 3600-beam scans): the once-per-map precomputation. One iteration is one map.
/// - BM_SectorLocalize/<map>: localize_in_sectors() on global 360-beam scans (8 m, 1 cm
///   Gaussian noise) from 16 poses of the sector protocol (sample_polygon_pose, 0.3 m from the
///   walls, seed 1), one scan per iteration in turn: the label, the label and skeleton matches,
///   and the residual of every candidate. Counters: found (share of the 16 scans with a fix)
///   and candidates (mean).
/// - BM_SectorCorrelationLocalize/<map>: the same scans through SectorCorrelationEstimator
///   (the fix, then the 2.5 cm local correlation search of sectors+correlation).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/sector_protocol.hpp"
#include "gridloc/engine/sectors/estimator.hpp"
#include "gridloc/engine/sectors/localization.hpp"
#include "gridloc/sensors/scan_disturbances.hpp"

namespace gridloc::bench {
namespace {

const char* const kMaps[] = {"room_rect", "room_l", "room_furnished", "office"};

/// The office's rows (index 3) take seconds to set up (its sectors: 3.6 s each time), so
/// they run only with GRIDLOC_BENCH_FULL=1, like the other slow rows, keeping bench_smoke short.
int last_map() {
  const char* v = std::getenv("GRIDLOC_BENCH_FULL");
  return v != nullptr && std::string(v) == "1" ? 3 : 2;
}

PolygonMap polygon_map(int index) {
  return load_polygon_map(std::string(GRIDLOC_BENCH_MAPS_DIR) + "/polygons/" + kMaps[index] +
                          ".yaml");
}

std::vector<RangeScan> protocol_scans(const PolygonMap& map) {
  Rng rng(1);
  std::vector<RangeScan> scans;
  for (int i = 0; i < 16; ++i) {
    const Pose2 truth = sample_polygon_pose(map, 0.3, rng);
    RangeScan scan = polygon_scan(map, truth, 360, 8.0);
    add_range_noise(scan, 0.01, rng.next());
    scans.push_back(std::move(scan));
  }
  return scans;
}

void BM_ComputeSectors(benchmark::State& state) {
  const PolygonMap map = polygon_map(static_cast<int>(state.range(0)));
  state.SetLabel(kMaps[state.range(0)]);
  for (auto _ : state) benchmark::DoNotOptimize(compute_sectors(map));
}
BENCHMARK(BM_ComputeSectors)->DenseRange(0, last_map())->Unit(benchmark::kMillisecond);

void BM_SectorLocalize(benchmark::State& state) {
  const PolygonMap map = polygon_map(static_cast<int>(state.range(0)));
  state.SetLabel(kMaps[state.range(0)]);
  const SectorMap sectors = compute_sectors(map);
  const std::vector<RangeScan> scans = protocol_scans(map);
  std::size_t i = 0;
  double found = 0.0, candidates = 0.0, runs = 0.0;
  for (auto _ : state) {
    const SectorFix f = localize_in_sectors(sectors, scans[i++ % scans.size()]);
    found += f.found ? 1.0 : 0.0;
    candidates += f.candidates;
    runs += 1.0;
  }
  state.counters["found"] = found / runs;
  state.counters["candidates"] = candidates / runs;
}
BENCHMARK(BM_SectorLocalize)->DenseRange(0, last_map())->Unit(benchmark::kMillisecond);

void BM_SectorCorrelationLocalize(benchmark::State& state) {
  const PolygonMap map = polygon_map(static_cast<int>(state.range(0)));
  state.SetLabel(kMaps[state.range(0)]);
  auto sectors = std::make_shared<const SectorEstimator>(map);
  CorrelationOptions fine;
  fine.resolution = SectorEvalOptions{}.refinement_resolution;
  fine.reach_m = 8.0;
  auto local = std::make_shared<const CorrelationEstimator>(
      rasterize_polygon_map(map, fine.resolution), fine);
  const SectorCorrelationEstimator estimator(sectors, local);
  const std::vector<RangeScan> scans = protocol_scans(map);
  SearchWindow window;
  window.center = {0.0, 0.0, 0.0};
  window.half_xy = 100.0;
  window.half_theta = 3.14159;
  std::size_t i = 0;
  for (auto _ : state) {
    const Observation obs{{}, scans[i++ % scans.size()]};
    benchmark::DoNotOptimize(estimator.estimate(obs, window));
  }
}
BENCHMARK(BM_SectorCorrelationLocalize)->DenseRange(0, last_map())->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gridloc::bench
