/// The peer-comparison case ../shared/bench-cases/apartment (see its README.md): a 20 x 15 m
/// map at 0.05 m and two 360-beam laser scans (max range 8 m), scan-only estimator at 0.05 m.
/// - BM_ApartmentPrecompute/<strategy>: estimator construction (global grids of 3 levels,
///   padded by the 8 m reach; bnb adds its bound pyramid). Not part of the timings below.
/// - BM_ApartmentScanGrid/res_cm:<r>: rasterize_scan for the 121 headings of the windowed
///   search of case 1 (items = local grids built), the cost that dominates the scan search.
/// - BM_ApartmentScan/<case>/<strategy>: one estimate() per iteration. case1 and case2 search
///   +-0.5 m, +-0.3 rad at 0.005 rad from the README's start poses; case1_wide searches +-2 m,
///   +-30 deg at the step that moves the farthest return by one cell (see wide_step()).
/// Counters: pos_err_mm and heading_err_deg of the refined pose against truth.txt,
/// poses_per_loc (poses scored), headings, step_theta_mrad, median_ms (estimator's own).
/// Without ../shared every one of them is skipped with an error saying so.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "bench_scenarios.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc::bench {
namespace {

constexpr double kResolution = 0.05;    // README: estimator resolution 0.05 m
constexpr double kMaxRange = 8.0;       // README: a range of 8.0 or more is no return
constexpr double kStepTheta = 0.005;    // README: windowed search heading step (rad)
constexpr int kWindowedHeadings = 121;  // +-0.3 rad at 0.005 rad

struct Case {
  const char* name;
  const char* dir;  ///< holds scan.csv and truth.txt, relative to the case folder
  Pose2 start;
  double half_xy;
  double half_theta;
  bool wide;
};

// Start poses from the README. The wide case gives only "1.44 m and 0.35 rad off" the truth
// (2.30, 0.10, 0.600): we use the offset (+1.20, -0.80, +0.35), 1.442 m, a free cell.
const Case kCases[] = {
    {"case1", ".", {2.53, -0.07, 0.70}, 0.5, 0.3, false},
    {"case2", "case2", {9.06, 8.34, -2.25}, 0.5, 0.3, false},
    {"case1_wide", ".", {3.50, -0.70, 0.95}, 2.0, 0.523598775598, true},  // +-30 deg
};

std::filesystem::path case_folder() {
  return std::filesystem::path(GRIDLOC_BENCH_SHARED_DIR) / "bench-cases" / "apartment";
}

/// The shared inputs, loaded once; `error` says why they are missing.
struct Inputs {
  OccupancyMap map;
  std::map<std::string, RangeScan> scans;  ///< by Case::dir
  std::map<std::string, Pose2> truths;     ///< by Case::dir
  std::string error;
};

Pose2 load_truth(const std::filesystem::path& path) {
  std::ifstream in(path);
  Pose2 p;
  if (!(in >> p.x >> p.y >> p.theta)) throw Error("cannot read x y theta from " + path.string());
  return p;
}

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    const std::filesystem::path dir = case_folder();
    if (!std::filesystem::exists(dir / "apartment.yaml")) {
      r.error = "shared bench case not found at " + dir.string() +
                " (../shared is absent); apartment benchmarks skipped";
      return r;
    }
    try {
      r.map = load_ros_map((dir / "apartment.yaml").string());
      for (const char* sub : {".", "case2"}) {
        r.scans[sub] = load_scan_csv((dir / sub / "scan.csv").string(), kMaxRange);
        r.truths[sub] = load_truth(dir / sub / "truth.txt");
      }
    } catch (const std::exception& e) {
      r.error = std::string("apartment bench case unreadable: ") + e.what();
    }
    return r;
  }();
  return in;
}

CorrelationOptions scan_options(SearchStrategy strategy) {
  CorrelationOptions o;
  o.strategy = strategy;
  o.resolution = kResolution;
  o.reach_m = kMaxRange;
  return o;
}

const CorrelationEstimator& scan_estimator(SearchStrategy strategy) {
  static std::map<SearchStrategy, std::unique_ptr<CorrelationEstimator>> cache;
  auto& slot = cache[strategy];
  if (!slot) slot = std::make_unique<CorrelationEstimator>(inputs().map, scan_options(strategy));
  return *slot;
}

/// Wide-window heading step: the angle that moves the farthest return by one cell,
/// acos(1 - res^2 / (2 r^2)) (Cartographer's choice for its correlative matchers): 6.4 mrad
/// (0.37 deg) for case 1's 7.84 m. The windowed 0.005 rad (README) is finer than that.
double wide_step(const RangeScan& scan) {
  double far = 0.0;
  for (double r : scan.ranges) {
    if (r < scan.max_range) far = std::max(far, r);
  }
  return std::acos(1.0 - kResolution * kResolution / (2.0 * far * far));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

void BM_ApartmentPrecompute(benchmark::State& state, SearchStrategy strategy) {
  const Inputs& in = inputs();
  if (!in.error.empty()) {
    state.SkipWithError(in.error.c_str());
    return;
  }
  for (auto _ : state) {
    // The constructor takes the map by value: its copy is part of the cost.
    const CorrelationEstimator est(in.map, scan_options(strategy));
    benchmark::DoNotOptimize(&est.level(0));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["map_cells"] = static_cast<double>(in.map.geometry.size());
}

void BM_ApartmentScanGrid(benchmark::State& state) {
  const Inputs& in = inputs();
  if (!in.error.empty()) {
    state.SkipWithError(in.error.c_str());
    return;
  }
  const double resolution = static_cast<double>(state.range(0)) / 100.0;
  const RangeScan& scan = in.scans.at(".");
  const Pose2 start = kCases[0].start;
  const double theta0 = start.theta - (kWindowedHeadings / 2) * kStepTheta;
  double cells = 0.0;
  for (auto _ : state) {
    for (int it = 0; it < kWindowedHeadings; ++it) {
      const SparseLocalGrid g = rasterize_scan(scan, theta0 + it * kStepTheta, resolution);
      benchmark::DoNotOptimize(g.value.data());
      cells += static_cast<double>(g.size());
    }
  }
  using benchmark::Counter;
  state.SetItemsProcessed(state.iterations() * kWindowedHeadings);
  state.counters["cells_per_grid"] = Counter(cells / kWindowedHeadings, Counter::kAvgIterations);
}

void BM_ApartmentScan(benchmark::State& state, const Case& c, SearchStrategy strategy) {
  const Inputs& in = inputs();
  if (!in.error.empty()) {
    state.SkipWithError(in.error.c_str());
    return;
  }
  Observation obs;
  obs.scan = in.scans.at(c.dir);
  const Pose2& truth = in.truths.at(c.dir);
  const double step = c.wide ? wide_step(*obs.scan) : kStepTheta;
  const SearchWindow window{c.start, c.half_xy, c.half_theta, kResolution, step};
  const CorrelationEstimator& est = scan_estimator(strategy);

  std::vector<double> elapsed_ms;
  std::optional<Estimate> last;
  double cells = 0.0;
  for (auto _ : state) {
    last = est.estimate(obs, window);
    benchmark::DoNotOptimize(last->pose);
    cells += static_cast<double>(last->stats.cells_scored);
    elapsed_ms.push_back(last->stats.elapsed_ms);
  }
  if (!last) return;
  // The estimator is deterministic: every iteration gives this same estimate.
  using benchmark::Counter;
  state.SetItemsProcessed(state.iterations());
  state.counters["pos_err_mm"] =
      1000.0 * std::hypot(last->pose.x - truth.x, last->pose.y - truth.y);
  state.counters["heading_err_deg"] =
      std::abs(normalize_angle(last->pose.theta - truth.theta)) * 180.0 / std::numbers::pi;
  state.counters["poses_per_loc"] = static_cast<double>(last->stats.poses_scored);
  state.counters["cells_per_s"] = Counter(cells, Counter::kIsRate);
  state.counters["headings"] = static_cast<double>(2 * std::lround(c.half_theta / step) + 1);
  state.counters["step_theta_mrad"] = 1000.0 * step;
  state.counters["median_ms"] = median(std::move(elapsed_ms));
}

const bool registered = [] {
  for (SearchStrategy s : {SearchStrategy::Multires, SearchStrategy::BranchAndBound}) {
    benchmark::RegisterBenchmark(("BM_ApartmentPrecompute/" + strategy_name(s)).c_str(),
                                 BM_ApartmentPrecompute, s)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_ApartmentScanGrid", BM_ApartmentScanGrid)
      ->ArgName("res_cm")
      ->Arg(5)
      ->Arg(10)
      ->Arg(20)
      ->Unit(benchmark::kMillisecond);
  for (const Case& c : kCases) {
    for (SearchStrategy s :
         {SearchStrategy::Multires, SearchStrategy::BranchAndBound, SearchStrategy::Exhaustive}) {
      const bool exhaustive = s == SearchStrategy::Exhaustive;
      if (exhaustive && std::string(c.name) != "case1") continue;  // seconds per call
      const std::string name = "BM_ApartmentScan/" + std::string(c.name) + "/" + strategy_name(s);
      auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_ApartmentScan, c, s)
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
      if (exhaustive) b->Iterations(1);
    }
  }
  return true;
}();

}  // namespace
}  // namespace gridloc::bench
