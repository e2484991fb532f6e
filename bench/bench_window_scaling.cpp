/// BM_WindowScaling/room_l/<strategy>/<half_xy cm>: how multires, exhaustive and bnb scale
/// with the translation window (half sizes 0.4, 0.8, 1.6 m at +-45 deg, 10 cm and 5 deg
/// steps). The same 16 trials throughout; only the prior offset scales with the window.
#include <string>

#include "bench_scenarios.hpp"

namespace gridloc::bench {
namespace {

constexpr double kHalfTheta = 0.785398163397;  // 45 deg

void BM_WindowScaling(benchmark::State& state, SearchStrategy s) {
  const double half_xy = static_cast<double>(state.range(0)) / 100.0;
  localize_loop(state, "room_l", s, half_xy, kHalfTheta);
}

const bool registered = [] {
  for (SearchStrategy s :
       {SearchStrategy::Multires, SearchStrategy::Exhaustive, SearchStrategy::BranchAndBound}) {
    const std::string name = "BM_WindowScaling/room_l/" + to_string(s);
    benchmark::RegisterBenchmark(name.c_str(), BM_WindowScaling, s)
        ->ArgName("half_cm")
        ->Arg(40)
        ->Arg(80)
        ->Arg(160)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
