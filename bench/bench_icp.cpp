/// Robust scan-to-scan ICP (gridloc::match_scans, seed 004), timed per scan pair:
/// - BM_IcpHallway/outliers_pct:<p>: seed 004 §4's simulation, a 720-beam (0.5 deg, 8 m)
///   noise-free scan of seed004_hallway() at (0, 0, 0) as reference and one at
///   (0.5 m, -0.2 m, 20 deg) as current, with p % of the current points replaced by seeded
///   random points within 3 m (as tests/test_robust_icp.cpp's with_outliers), matched from a
///   zero prior with default options. One iteration is one match. Counters: error_mm
///   (position error), error_deg, iterations (ICP iterations of the match).
/// - BM_IcpIntelPairs: every Intel lab relation that falls on two scans of the corrected Intel
///   log (../shared/datasets/xiaofeng419_SLAM-2D-LIDAR-SCAN, or $GRIDLOC_SHARED_DIR/datasets/...),
///   matched from the logged relative motion as prior (no noise). One iteration matches all
///   pairs; counters: pairs, time_per_pair (s, with SI prefix), and from the last iteration
///   converged (share) and error_mm / error_deg (mean against the relations). Skipped with an error
///   when the data are absent.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench_scenarios.hpp"
#include "gridloc/engine/relation_eval.hpp"
#include "gridloc/engine/robust_icp.hpp"
#include "gridloc/sensors/carmen_log.hpp"
#include "gridloc/sensors/segment_world.hpp"
#include "gridloc/sensors/slam_relations.hpp"

namespace gridloc::bench {
namespace {

using Points = std::vector<Eigen::Vector2d>;

const Pose2 kMotion{0.5, -0.2, deg2rad(20.0)};  // seed 004 §4

/// The hallway's returns at `pose` in the robot frame, in beam order: 720 beams 0.5 deg apart
/// from -180 deg, 8 m max range (as tests/test_robust_icp.cpp's scan_at).
Points hallway_scan(const Pose2& pose) {
  static const std::vector<WallSegment> walls = seed004_hallway();
  return scan_returns(simulate_segment_scan(walls, pose, 720, deg2rad(-180.0), deg2rad(0.5), 8.0));
}

/// Replaces `share` of the points by random points within 3 m of the robot (seeded).
Points with_outliers(Points pts, double share, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::size_t> idx(pts.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::shuffle(idx.begin(), idx.end(), rng);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const auto n = static_cast<std::size_t>(share * static_cast<double>(pts.size()));
  for (std::size_t k = 0; k < n; ++k) pts[idx[k]] = {u(rng), u(rng)};
  return pts;
}

void BM_IcpHallway(benchmark::State& state) {
  const double share = static_cast<double>(state.range(0)) / 100.0;
  const Points ref = hallway_scan({0, 0, 0});
  const Points cur = with_outliers(hallway_scan(kMotion), share, 4);
  IcpResult r;
  for (auto _ : state) {
    r = match_scans(ref, cur, Pose2{}, IcpOptions{});
    benchmark::DoNotOptimize(r);
  }
  state.counters["error_mm"] = 1000.0 * std::hypot(r.pose.x - kMotion.x, r.pose.y - kMotion.y);
  state.counters["error_deg"] = rad2deg(std::abs(normalize_angle(r.pose.theta - kMotion.theta)));
  state.counters["iterations"] = r.iterations;
}
BENCHMARK(BM_IcpHallway)->ArgName("outliers_pct")->Arg(0)->Arg(30)->Unit(benchmark::kMicrosecond);

/// The shared folder: $GRIDLOC_SHARED_DIR when set, else ../shared next to the source tree.
std::filesystem::path shared_dir() {
  const char* env = std::getenv("GRIDLOC_SHARED_DIR");
  if (env != nullptr && *env != '\0') return env;
  return GRIDLOC_BENCH_SHARED_DIR;
}

struct IntelPairs {
  std::vector<Points> reference, current;
  std::vector<Pose2> prior, truth;
  std::string error;
};

const IntelPairs& intel_pairs() {
  static const IntelPairs in = [] {
    IntelPairs r;
    const std::filesystem::path dir = shared_dir() / "datasets" / "xiaofeng419_SLAM-2D-LIDAR-SCAN";
    const std::filesystem::path log_path = dir / "intel.gfs.log";
    const std::filesystem::path rel_path = dir / "intel.relations";
    if (!std::filesystem::exists(log_path) || !std::filesystem::exists(rel_path)) {
      r.error = "Intel log or relations not found in " + dir.string() +
                " (../shared is absent; set GRIDLOC_SHARED_DIR); BM_IcpIntelPairs skipped";
      return r;
    }
    try {
      const CarmenLog log = load_carmen_log(log_path.string());
      const auto pairs =
          pair_relations(load_slam_relations(rel_path.string()), log, 976052857.337311, 0.002);
      for (const RelationPair& p : pairs) {
        const LaserRecord& a = log.lasers[p.first];
        const LaserRecord& b = log.lasers[p.second];
        r.reference.push_back(scan_returns(a.scan));
        r.current.push_back(scan_returns(b.scan));
        r.prior.push_back(relative_pose(a.laser_pose, b.laser_pose));
        r.truth.push_back(p.relation.motion);
      }
      if (pairs.empty()) r.error = "no Intel relation falls on two scans of the log";
    } catch (const std::exception& e) {
      r.error = std::string("cannot load the Intel data: ") + e.what();
    }
    return r;
  }();
  return in;
}

void BM_IcpIntelPairs(benchmark::State& state) {
  const IntelPairs& in = intel_pairs();
  if (!in.error.empty()) {
    state.SkipWithError(in.error.c_str());
    return;
  }
  const std::size_t n = in.reference.size();
  std::vector<IcpResult> results(n);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      results[i] = match_scans(in.reference[i], in.current[i], in.prior[i], IcpOptions{});
    }
    benchmark::DoNotOptimize(results.data());
  }
  double converged = 0.0, err_m = 0.0, err_deg = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Pose2 e = relative_pose(in.truth[i], results[i].pose);
    converged += results[i].converged ? 1.0 : 0.0;
    err_m += std::hypot(e.x, e.y);
    err_deg += rad2deg(std::abs(e.theta));
  }
  const double pairs = static_cast<double>(n);
  state.counters["pairs"] = pairs;
  // kIsRate | kInvert: seconds per pair (printed with its SI prefix, e.g. 177us).
  state.counters["time_per_pair"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * pairs,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["converged"] = converged / pairs;
  state.counters["error_mm"] = 1000.0 * err_m / pairs;
  state.counters["error_deg"] = err_deg / pairs;
}
BENCHMARK(BM_IcpIntelPairs)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gridloc::bench
