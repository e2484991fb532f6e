/// Once-per-map costs. BM_Precompute/<map>: CorrelationEstimator construction with default
/// options (global grids of the 3 levels, resampled, thinned and padded; the default strategy,
/// bnb, adds its bound pyramid). BM_GlobalGrid/<map>/<model>:
/// make_global_grid alone at 0.10 m, thinned (seed 001 §5) vs raw.
#include <string>

#include "bench_scenarios.hpp"
#include "gridloc/grids/evidence.hpp"

namespace gridloc::bench {
namespace {

constexpr const char* kMaps[] = {"room_rect", "room_l", "room_furnished", "apartment_small"};

void BM_Precompute(benchmark::State& state, const std::string& name) {
  const OccupancyMap& map = bundled_map(name);
  const SonarRing& ring = wheelchair_ring();
  for (auto _ : state) {
    // The constructor takes the map and ring by value: their copies are part of the cost.
    CorrelationEstimator est(map, ring);
    benchmark::DoNotOptimize(&est.level(0));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["map_cells"] = static_cast<double>(map.geometry.size());
}

void BM_GlobalGrid(benchmark::State& state, const std::string& name, GlobalModel model) {
  const OccupancyMap& map = bundled_map(name);
  for (auto _ : state) {
    const EvidenceGrid g = make_global_grid(map, 0.1, model);
    benchmark::DoNotOptimize(g.cells.data());
  }
  state.SetItemsProcessed(state.iterations());
}

const bool registered = [] {
  for (const char* map : kMaps) {
    const std::string m(map);
    benchmark::RegisterBenchmark(("BM_Precompute/" + m).c_str(), BM_Precompute, m)
        ->Unit(benchmark::kMillisecond);
  }
  for (const char* map : kMaps) {
    const std::string m(map);
    benchmark::RegisterBenchmark(("BM_GlobalGrid/" + m + "/thinned").c_str(), BM_GlobalGrid, m,
                                 GlobalModel::Thinned)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_GlobalGrid/" + m + "/raw").c_str(), BM_GlobalGrid, m,
                                 GlobalModel::Raw)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
