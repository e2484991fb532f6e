#pragma once
/// Shared inputs of the benchmarks: bundled maps, the wheelchair ring, a fixed set of
/// pre-simulated realistic observations (seed 001 §4 protocol), cached estimators, and the
/// localization loop that the window benchmarks time.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::bench {

/// One pre-simulated trial: true pose, its readings and a unit prior offset in [-1, 1]^3 that
/// a window's half sizes scale into a prior (so every window size sees the same trials).
struct Trial {
  Pose2 truth;
  Observation observation;
  double ux = 0.0, uy = 0.0, ut = 0.0;
};

/// The map `name` (e.g. "room_l") from the bundled maps folder; loaded once, then cached.
const OccupancyMap& bundled_map(const std::string& name);

/// The 14-sonar wheelchair ring; loaded once.
const SonarRing& wheelchair_ring();

/// 16 trials on map `name`: poses from sample_free_pose (0.25 m clearance) and realistic
/// sonar noise, all drawn from one fixed Rng seed; computed once per map.
const std::vector<Trial>& trials(const std::string& name);

/// The search window of `trial` with the given half sizes (m, rad) at 10 cm / 5 deg steps,
/// its centre the perturbed prior, pulled back onto the map if it left it.
SearchWindow window_for(const Trial& trial, const OccupancyMap& map, double half_xy,
                        double half_theta);

/// A correlation estimator with default options, `strategy` and `threads` on map `name`;
/// cached.
const CorrelationEstimator& estimator(const std::string& name, SearchStrategy strategy,
                                      int threads = 1);

/// Times one localization per iteration, cycling through trials(name); sets items (one
/// localization each), the rates poses_per_s and cells_per_s, median_ms (median of the
/// estimator's own elapsed_ms over the iterations), and, from one untimed pass over all 16
/// trials, success (within 10 cm and 7 deg), pos_err_mm (mean), poses_per_loc (poses scored)
/// and same_as_exh: the fraction of trials whose pose, lattice pose and score equal, bit for
/// bit, those of the single-threaded exhaustive search in the same window.
void localize_loop(benchmark::State& state, const std::string& name, SearchStrategy strategy,
                   double half_xy, double half_theta, int threads = 1);

}  // namespace gridloc::bench
