/// BM_OrientedGridConstruction/res_cm:<r>: rasterize_oriented for the 19 headings of the seed
/// window (+-45 deg in 5 deg steps) from one observation, at the finest level (10 cm) and the
/// multires coarse levels (20, 40 cm). Items are local grids built.
#include "bench_scenarios.hpp"
#include "gridloc/sensors/sonar_model.hpp"

namespace gridloc::bench {
namespace {

constexpr int kHeadings = 19;
constexpr double kStepTheta = 0.0872664625997;  // 5 deg

void BM_OrientedGridConstruction(benchmark::State& state) {
  const double resolution = static_cast<double>(state.range(0)) / 100.0;
  const SonarRing& ring = wheelchair_ring();
  const Trial& trial = trials("room_l").front();
  const double theta0 = trial.truth.theta - (kHeadings / 2) * kStepTheta;
  double cells = 0.0;
  for (auto _ : state) {
    for (int it = 0; it < kHeadings; ++it) {
      const SparseLocalGrid g =
          rasterize_oriented(ring, trial.observation.ranges, theta0 + it * kStepTheta, resolution);
      benchmark::DoNotOptimize(g.value.data());
      cells += static_cast<double>(g.size());
    }
  }
  using benchmark::Counter;
  state.SetItemsProcessed(state.iterations() * kHeadings);
  state.counters["cells_per_grid"] = Counter(cells / kHeadings, Counter::kAvgIterations);
}

BENCHMARK(BM_OrientedGridConstruction)
    ->ArgName("res_cm")
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gridloc::bench
