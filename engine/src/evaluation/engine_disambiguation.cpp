// Seed 002 with the engine in the loop, as a protocol (see engine_disambiguation.hpp).
#include "gridloc/engine/evaluation/engine_disambiguation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

struct TrialOutcome {
  bool error = false;
  int hypotheses = 0;
  bool truth_seeded = false, true_survived = false, wrong_answer = false, resolved = false;
  bool noise_free_resolved = false;
  double path_length = 0.0, noise_free_path_length = 0.0, ms = 0.0;
  int stops = 0;
};

TrialOutcome run_trial(const EngineLoop& loop, const Pose2& truth, std::vector<Pose2> hypotheses,
                       std::uint64_t seed) {
  const auto begin = std::chrono::steady_clock::now();
  const EngineLoopRun run = loop.run(truth, std::move(hypotheses), seed);
  TrialOutcome outcome;
  outcome.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  outcome.hypotheses = static_cast<int>(run.hypotheses.size());
  outcome.truth_seeded = run.true_hypothesis >= 0;
  const std::vector<int>& left = run.plan.remaining;
  outcome.true_survived = std::find(left.begin(), left.end(), run.true_hypothesis) != left.end();
  outcome.resolved = run.plan.resolved;
  outcome.wrong_answer = run.plan.resolved && left.front() != run.true_hypothesis;
  outcome.path_length = run.plan.path_length;
  outcome.stops = static_cast<int>(run.plan.stops.size());
  outcome.noise_free_resolved = run.noise_free.resolved;
  outcome.noise_free_path_length = run.noise_free.path_length;
  return outcome;
}

double mean_of(const std::vector<TrialOutcome>& outcomes,
               const std::function<double(const TrialOutcome&)>& value) {
  if (outcomes.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const TrialOutcome& outcome : outcomes) sum += value(outcome);
  return sum / static_cast<double>(outcomes.size());
}

double median_ms(const std::vector<TrialOutcome>& outcomes) {
  std::vector<double> ms;
  ms.reserve(outcomes.size());
  for (const TrialOutcome& outcome : outcomes) ms.push_back(outcome.ms);
  if (ms.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(ms.begin(), ms.end());
  return ms.size() % 2 == 1 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
}

EngineDisambiguationResult summarize(const std::string& name, int drawn,
                                     const std::vector<TrialOutcome>& outcomes) {
  EngineDisambiguationResult row;
  row.map = name;
  row.trials = static_cast<int>(outcomes.size());
  row.drawn = drawn;
  for (const TrialOutcome& outcome : outcomes) {
    row.truth_seeded += outcome.truth_seeded ? 1 : 0;
    row.wrong_answers += outcome.wrong_answer ? 1 : 0;
    row.errors += outcome.error ? 1 : 0;
  }
  row.true_survived_rate = mean_of(outcomes, [](const TrialOutcome& o) { return o.true_survived; });
  row.resolved_rate = mean_of(outcomes, [](const TrialOutcome& o) { return o.resolved; });
  row.mean_hypotheses = mean_of(outcomes, [](const TrialOutcome& o) { return o.hypotheses; });
  row.mean_path_length = mean_of(outcomes, [](const TrialOutcome& o) { return o.path_length; });
  row.mean_noise_free_path_length =
      mean_of(outcomes, [](const TrialOutcome& o) { return o.noise_free_path_length; });
  row.noise_free_resolved_rate =
      mean_of(outcomes, [](const TrialOutcome& o) { return o.noise_free_resolved; });
  row.mean_stops = mean_of(outcomes, [](const TrialOutcome& o) { return o.stops; });
  row.median_ms = median_ms(outcomes);
  return row;
}

/// Every trial on one map: poses drawn until `trials` of them are ambiguous.
EngineDisambiguationResult run_map(const EvalMap& map, const SonarRing& ring,
                                   const EngineDisambiguationOptions& options,
                                   const std::function<void(int)>& trial_done) {
  const EngineLoop loop(map.map, ring, options.loop);
  Rng rng(options.seed);
  std::vector<TrialOutcome> outcomes;
  int drawn = 0;
  const int attempts = options.trials * options.attempts_per_trial;
  while (static_cast<int>(outcomes.size()) < options.trials && drawn < attempts) {
    ++drawn;
    const Pose2 truth = sample_free_pose(map.map, ring, options.clearance_m, rng);
    const std::uint64_t seed = options.seed * 1000003u + static_cast<std::uint64_t>(drawn);
    std::vector<Pose2> hypotheses = loop.hypotheses(loop.observe(truth, seed));
    if (hypotheses.size() < 2) continue;
    try {
      outcomes.push_back(run_trial(loop, truth, std::move(hypotheses), seed));
    } catch (const Error&) {  // one trial's failure is a result, not the protocol's end
      TrialOutcome failed;
      failed.error = true;
      failed.true_survived = true;  // nothing was ruled out
      outcomes.push_back(failed);
    }
    trial_done(static_cast<int>(outcomes.size()));
  }
  return summarize(map.name, drawn, outcomes);
}

}  // namespace

void validate(const EngineDisambiguationOptions& options) {
  if (options.trials < 1 || options.trials > 1000000) {
    throw Error("engine disambiguation: trials must be in [1, 1000000]");
  }
  if (options.attempts_per_trial < 1 || options.attempts_per_trial > 1000) {
    throw Error("engine disambiguation: attempts_per_trial must be in [1, 1000]");
  }
  validate(options.loop);
}

std::vector<EngineDisambiguationResult> run_engine_disambiguation(
    const std::vector<EvalMap>& maps, const SonarRing& ring,
    const EngineDisambiguationOptions& options, const std::function<void(int, int)>& progress) {
  validate(options);
  std::vector<EngineDisambiguationResult> results;
  const int total = options.trials * static_cast<int>(maps.size());
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const int before = options.trials * static_cast<int>(m);
    results.push_back(run_map(maps[m], ring, options, [&](int done) {
      if (progress) progress(before + done, total);
    }));
  }
  return results;
}

}  // namespace gridloc
