/// BM_SonarSeedWindow/<map>/<strategy>: one localization in seed 001's window (+-0.8 m,
/// +-45 deg, 10 cm, 5 deg) per iteration, cycling through 16 pre-simulated realistic
/// observations; multires (the default) and exhaustive (the exact reference) side by side.
#include <string>

#include "bench_scenarios.hpp"

namespace gridloc::bench {
namespace {

constexpr double kHalfXy = 0.8;
constexpr double kHalfTheta = 0.785398163397;  // 45 deg

void BM_SonarSeedWindow(benchmark::State& state, const std::string& map, SearchStrategy s) {
  localize_loop(state, map, s, kHalfXy, kHalfTheta);
}

const bool registered = [] {
  for (const char* map : {"room_rect", "room_l", "room_furnished"}) {
    for (SearchStrategy s : {SearchStrategy::Multires, SearchStrategy::Exhaustive}) {
      const std::string name = "BM_SonarSeedWindow/" + std::string(map) + "/" + strategy_name(s);
      benchmark::RegisterBenchmark(name.c_str(), BM_SonarSeedWindow, std::string(map), s)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
