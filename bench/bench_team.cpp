/// Seed 003's team solve (issue 16's target: <= 10 ms for 4 robots): random teams of the team
/// protocol on the T-room (maps/polygons/t_room.yaml), IR sensing with Table II noise.
/// - BM_TeamSolve/<robots>: one iteration = localize_team on a prepared team (candidates
///   already placed, links measured): the tree, the pairs, their join, the checks, the refit.
/// - BM_TeamFromScans/<robots>: one iteration = every robot's features and candidates from
///   its scan, then the team solve (what `gridloc team --robots` does after reading).
#include <benchmark/benchmark.h>

#include <vector>

#include "gridloc/engine/evaluation/team_protocol.hpp"

namespace gridloc::bench {
namespace {

const TeamWorld& t_room() {
  static const TeamWorld world =
      make_team_world(load_polygon_map(GRIDLOC_BENCH_MAPS_DIR "/polygons/t_room.yaml"));
  return world;
}

/// Eight teams of `robots`, the protocol's draws.
std::vector<TeamCase> teams(const TeamSimulator& simulator, int robots) {
  TeamProtocolOptions options;
  std::vector<TeamCase> cases;
  for (int k = 0; k < 8; ++k)
    cases.push_back(simulator.simulate(draw_team(simulator, robots, options, 100 + k), 100 + k));
  return cases;
}

void BM_TeamSolve(benchmark::State& state) {
  const TeamSimulator simulator(t_room(), {});
  const std::vector<TeamCase> cases = teams(simulator, static_cast<int>(state.range(0)));
  std::size_t k = 0;
  for (auto _ : state) {
    const TeamCase& team = cases[k++ % cases.size()];
    benchmark::DoNotOptimize(localize_team(team.robots, team.links, t_room().features));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TeamSolve)->DenseRange(2, 4)->Unit(benchmark::kMillisecond);

void BM_TeamFromScans(benchmark::State& state) {
  const TeamSimulator simulator(t_room(), {});
  const std::vector<TeamCase> cases = teams(simulator, static_cast<int>(state.range(0)));
  std::size_t k = 0;
  for (auto _ : state) {
    const TeamCase& team = cases[k++ % cases.size()];
    std::vector<TeamRobot> robots;
    for (const RangeScan& scan : team.scans)
      robots.push_back(simulator.robot_from_scan(scan, nullptr));
    benchmark::DoNotOptimize(localize_team(robots, team.links, t_room().features));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TeamFromScans)->DenseRange(2, 4)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gridloc::bench
