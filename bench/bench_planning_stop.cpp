/// Seed 002's planning time per stop (issue 15's target: <= 100 ms on a 400-vertex office):
/// the first stop of COL or UAL with the hybrid strategy and 250 random points, on
/// random_office(1) (400 vertices) from an ambiguous start, per sensor range.
/// - BM_PlanningStop/<algorithm 0 col, 1 ual>/<range: 0 unlimited, else tenths of a cell>
///   /<threads>:
///   one iteration = one stop (overlay, U for UAL, the random points' info and distances, the
///   route there, the perfect sensor's elimination).
#include <benchmark/benchmark.h>

#include <vector>

#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"
#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/polygon_space.hpp"
#include "gridloc/engine/evaluation/disambiguation_protocol.hpp"

namespace gridloc::bench {
namespace {

void BM_PlanningStop(benchmark::State& state) {
  const double range = state.range(1) == 0 ? kUnlimitedRange : 0.1 * state.range(1);
  const PolygonMap office = random_office(1);
  const Area free_world = free_area(office);
  const Pose2 start = ambiguous_starts(office, 1, {kUnlimitedRange, range}, 7, 20000).front();
  const std::vector<Pose2> hypotheses = start_hypotheses(free_world, start, {range, false, 1e-6});
  const PolygonPlanningSpace space(free_world, {range, 1e-6, 16});
  MinimumDistanceOptions options;
  options.algorithm = state.range(0) == 0 ? SamplingAlgorithm::Col : SamplingAlgorithm::Ual;
  options.strategy = DistanceStrategy::Hybrid;
  options.points = 250;
  options.max_stops = 1;
  options.threads = static_cast<int>(state.range(2));
  const StopSensing sense = perfect_sensing(free_world, start, hypotheses, range);
  for (auto _ : state) {
    benchmark::DoNotOptimize(localize_with_minimum_travel(space, hypotheses, sense, options));
  }
  state.counters["hypotheses"] = static_cast<double>(hypotheses.size());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PlanningStop)
    ->ArgsProduct({{0, 1}, {0, 50, 20, 9}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gridloc::bench
