/// BM_SonarSeedWindow/<map>/<strategy>: one localization in seed 001's window (+-0.8 m,
/// +-45 deg, 10 cm, 5 deg) per iteration, cycling through 16 pre-simulated realistic
/// observations; multires (the default), exhaustive (the exact reference) and bnb (exact
/// branch and bound) side by side. On room_l every strategy also runs with
/// CorrelationOptions::threads 1 and 2 (BM_SonarSeedWindow/room_l/<strategy>/threads:<n>);
/// those rows time wall clock (UseRealTime) and process CPU (all threads).
#include <string>

#include "bench_scenarios.hpp"

namespace gridloc::bench {
namespace {

constexpr double kHalfXy = 0.8;
constexpr double kHalfTheta = 0.785398163397;  // 45 deg
constexpr const char* kThreadsMap = "room_l";

constexpr SearchStrategy kStrategies[] = {SearchStrategy::Multires, SearchStrategy::Exhaustive,
                                          SearchStrategy::BranchAndBound};

void BM_SonarSeedWindow(benchmark::State& state, const std::string& map, SearchStrategy s) {
  localize_loop(state, map, s, kHalfXy, kHalfTheta);
}

void BM_SonarSeedWindowThreads(benchmark::State& state, const std::string& map, SearchStrategy s) {
  localize_loop(state, map, s, kHalfXy, kHalfTheta, static_cast<int>(state.range(0)));
}

const bool registered = [] {
  for (const char* map : {"room_rect", "room_l", "room_furnished"}) {
    const std::string m(map);
    for (SearchStrategy s : kStrategies) {
      const std::string name = "BM_SonarSeedWindow/" + m + "/" + to_string(s);
      if (m == kThreadsMap) {
        benchmark::RegisterBenchmark(name.c_str(), BM_SonarSeedWindowThreads, m, s)
            ->ArgName("threads")
            ->Arg(1)
            ->Arg(2)
            ->UseRealTime()
            ->MeasureProcessCPUTime()
            ->Unit(benchmark::kMillisecond);
      } else {
        benchmark::RegisterBenchmark(name.c_str(), BM_SonarSeedWindow, m, s)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
