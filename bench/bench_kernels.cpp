/// The correlation kernel alone, one placed 360-beam scan scored at 1024 cells spread over a
/// 20 m x 16 m synthetic map (0.05 m), per summation path:
/// BM_CorrelateKernel/float: correlate_scalar on the float grids (what non-ternary grids use);
/// /int8_float: correlate_scalar on the int8 copies (double accumulation, one chain);
/// /fixed_scalar: correlate_fixed_scalar, the integer reference; /fixed_avx2: its AVX2
/// gather path (skipped without AVX2). All four return the same sums (tests), so the
/// ratios are the gain of each step. Counter cells_per_s: local cells read per second.
#include <string>
#include <vector>

#include "bench_scenarios.hpp"
#include "gridloc/engine/correlation/fixed_point_kernel.hpp"
#include "gridloc/engine/correlation/search.hpp"
#include "gridloc/grids/evidence.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "scan_sim.hpp"

namespace gridloc::bench {
namespace {

constexpr double kResolution = 0.05;
constexpr double kMaxRange = 8.0;
constexpr int kOrigins = 1024;

struct KernelCase {
  PaddedGrid grid;
  PlacedLocalGrid local;
  std::vector<std::ptrdiff_t> origins;  ///< flat padded-grid index of each scored cell
};

const KernelCase& kernel_case() {
  static const KernelCase c = [] {
    KernelCase k;
    const OccupancyMap map = synthetic_rooms(4, 4, 7);
    const EvidenceGrid global = make_global_grid(map, kResolution, GlobalModel::Thinned);
    k.grid = pad_grid(global, static_cast<int>(kMaxRange / kResolution) + 2);
    const RangeScan scan = simulate_scan(map, synthetic_rooms_truth(), 360, kMaxRange, 0.01, 3);
    k.local = place_points(scan_points(scan, ScanModelOptions{}), 0.3, k.grid);
    const int w = k.grid.grid.width();
    for (int i = 0; i < kOrigins; ++i) {  // a spread of cells, all inside the map
      const int x = (i * 37) % k.grid.width, y = (i * 101) % k.grid.height;
      k.origins.push_back(static_cast<std::ptrdiff_t>(y + k.grid.pad) * w + x + k.grid.pad);
    }
    return k;
  }();
  return c;
}

enum class Path { Float, Int8Float, FixedScalar, FixedAvx2, FixedAvx512 };

void BM_CorrelateKernel(benchmark::State& state, Path path) {
  const KernelCase& c = kernel_case();
  if (!c.grid.ternary() || c.local.fixed_shift < 0) {
    state.SkipWithError("the kernel case is not ternary / fixed point");
    return;
  }
  if ((path == Path::FixedAvx2 && !avx2_available()) ||
      (path == Path::FixedAvx512 && !avx512_available())) {
    state.SkipWithError("this CPU lacks the instruction set");
    return;
  }
  const PlacedLocalGrid& l = c.local;
  const std::vector<float> arc = c.grid.arc_float_cells(), all = c.grid.float_cells();
  std::size_t i = 0;
  for (auto _ : state) {
    const std::ptrdiff_t o = c.origins[i++ % c.origins.size()];
    double sum = 0.0;
    switch (path) {
      case Path::Float:
        sum = correlate_scalar(arc.data() + o, all.data() + o, l);
        break;
      case Path::Int8Float:
        sum = correlate_scalar(c.grid.arc_view8().data() + o, c.grid.grid8.data() + o, l);
        break;
      case Path::FixedScalar:
        sum = static_cast<double>(
            correlate_fixed_scalar(c.grid.arc_view8().data() + o, c.grid.grid8.data() + o,
                                   l.offset.data(), l.fixed.data(), l.arc_count, l.offset.size()));
        break;
      case Path::FixedAvx512:
        sum = static_cast<double>(
            correlate_fixed_avx512(c.grid.arc_view8().data() + o, c.grid.grid8.data() + o,
                                   l.offset.data(), l.fixed.data(), l.arc_count, l.offset.size()));
        break;
      case Path::FixedAvx2:
        sum = static_cast<double>(
            correlate_fixed_avx2(c.grid.arc_view8().data() + o, c.grid.grid8.data() + o,
                                 l.offset.data(), l.fixed.data(), l.arc_count, l.offset.size()));
        break;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["cells_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(l.offset.size()),
      benchmark::Counter::kIsRate);
  state.counters["cells"] = static_cast<double>(l.offset.size());
}

const bool registered = [] {
  const std::pair<const char*, Path> paths[] = {{"float", Path::Float},
                                                {"int8_float", Path::Int8Float},
                                                {"fixed_scalar", Path::FixedScalar},
                                                {"fixed_avx2", Path::FixedAvx2},
                                                {"fixed_avx512", Path::FixedAvx512}};
  for (const auto& [name, path] : paths) {
    benchmark::RegisterBenchmark((std::string("BM_CorrelateKernel/") + name).c_str(),
                                 BM_CorrelateKernel, path);
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
