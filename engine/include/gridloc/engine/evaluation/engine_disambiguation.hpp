#pragma once
/// Seed 002 with the engine in the loop, as a protocol (issue 15, beyond the paper): per map,
/// true starts drawn until the correlation engine's global search leaves look-alikes, each
/// run by an EngineLoop (noisy sensing and odometry, the engine's scores rule hypotheses out)
/// beside the same planner with noise-free sensing and motion.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/engine_loop.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"

namespace gridloc {

struct EngineDisambiguationOptions {
  /// Ambiguous starts per map: poses are drawn until this many leave at least two
  /// hypotheses (at most `attempts_per_trial` draws each).
  int trials = 100;
  int attempts_per_trial = 20;
  std::uint64_t seed = 1;
  double clearance_m = 0.3;  ///< true starts keep the footprint this far from walls
  EngineLoopOptions loop;    ///< the sensor, the engine, the planner, the noise
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const EngineDisambiguationOptions& options);

/// One map's results; the rates and means are NaN when no drawn pose was ambiguous.
struct EngineDisambiguationResult {
  std::string map;
  int trials = 0;                   ///< ambiguous starts run
  int drawn = 0;                    ///< poses drawn to find them (the rest were unique)
  int truth_seeded = 0;             ///< trials whose hypotheses held the truth
  double true_survived_rate = 0.0;  ///< the truth stood to the end (of trials)
  int wrong_answers = 0;
  /// Trials whose planning failed with a gridloc::Error (e.g. a refit that put the chair in
  /// no cell it can reach under some hypothesis); counted in `trials`, never as resolved.
  int errors = 0;              ///< resolved to a hypothesis that is not the truth
  double resolved_rate = 0.0;  ///< one hypothesis left
  double mean_hypotheses = 0.0;
  double mean_path_length = 0.0;             ///< engine in the loop
  double mean_noise_free_path_length = 0.0;  ///< the same starts, perfect sensing and motion
  double noise_free_resolved_rate = 0.0;
  double mean_stops = 0.0;
  double median_ms = 0.0;  ///< per trial, the engine-in-the-loop run
};

/// Runs the protocol on each map; `progress(done, total)` after every trial.
std::vector<EngineDisambiguationResult> run_engine_disambiguation(
    const std::vector<EvalMap>& maps, const SonarRing& ring,
    const EngineDisambiguationOptions& options, const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
