#include "eval_disambiguation.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "gridloc/engine/evaluation/disambiguation_protocol.hpp"
#include "gridloc/engine/evaluation/engine_disambiguation.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

double parse_range(const std::string& text) {
  if (text == "inf" || text == "unlimited") return kUnlimitedRange;
  double value = 0.0;
  if (!CLI::detail::lexical_cast(text, value) || !(value > 0.0)) {
    throw Error("--range: '" + text + "' is not a range > 0 (or inf)");
  }
  return value;
}

DisambiguationProtocolOptions protocol_options(const DisambiguationEvalArgs& args,
                                               std::uint64_t seed) {
  DisambiguationProtocolOptions options;
  options.environments = args.environments;
  options.starts = args.starts;
  options.repeats = args.repeats;
  options.points = args.points;
  options.seed = seed;
  options.ranges.clear();
  for (const std::string& range : args.ranges) options.ranges.push_back(parse_range(range));
  options.algorithms.clear();
  for (const std::string& name : args.algorithms) {
    options.algorithms.push_back(name == "col" ? SamplingAlgorithm::Col : SamplingAlgorithm::Ual);
  }
  options.strategies.clear();
  for (const std::string& name : args.strategies) {
    options.strategies.push_back(name == "weighted" ? DistanceStrategy::Weighted
                                                    : DistanceStrategy::Hybrid);
  }
  return options;
}

const char* algorithm_name(SamplingAlgorithm algorithm) {
  return algorithm == SamplingAlgorithm::Col ? "col" : "ual";
}

const char* strategy_name(DistanceStrategy strategy) {
  return strategy == DistanceStrategy::Weighted ? "weighted" : "hybrid";
}

nlohmann::json result_json(const DisambiguationProtocolResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const DisambiguationConfiguration& row : result.configurations) {
    rows.push_back({{"algorithm", algorithm_name(row.algorithm)},
                    {"strategy", strategy_name(row.strategy)},
                    {"points", row.points},
                    {"range", std::isfinite(row.range) ? nlohmann::json(row.range) : nullptr},
                    {"trials", row.trials},
                    {"mean_path_length", number_or_null(row.mean_path_length)},
                    {"resolved_rate", number_or_null(row.resolved_rate)},
                    {"mean_stops", number_or_null(row.mean_stops)},
                    {"mean_lower_bound", row.mean_lower_bound},
                    {"mean_bound_ratio", row.mean_bound_ratio},
                    {"mean_pairwise_bound", row.mean_pairwise_bound},
                    {"mean_pairwise_ratio", row.mean_pairwise_ratio},
                    {"mean_hypotheses", number_or_null(row.mean_hypotheses)},
                    {"median_ms", number_or_null(row.median_ms)},
                    {"mean_stop_ms", row.mean_stop_ms}});
  }
  return {{"protocol", "disambiguation"}, {"trials", result.trials}, {"configurations", rows}};
}

void print_table(const DisambiguationEvalArgs& args, const DisambiguationProtocolResult& result) {
  std::printf(
      "Seed 002 protocol: %d offices x %d starts x %d repeats = %d trials per configuration\n",
      args.environments, args.starts, args.repeats, result.trials);
  std::printf("%-4s %-9s %6s %6s %9s %8s %6s %8s %7s %8s %7s %6s %9s\n", "alg", "strategy",
              "points", "range", "path", "resolved", "stops", "bound", "ratio", "pairwise", "ratio",
              "hyps", "ms/stop");
  for (const DisambiguationConfiguration& row : result.configurations) {
    char range[16] = "inf";
    if (std::isfinite(row.range)) std::snprintf(range, sizeof range, "%g", row.range);
    std::printf("%-4s %-9s %6d %6s %9.3f %7.1f%% %6.2f %8.3f %7.2f %8.3f %7.2f %6.1f %9.2f\n",
                algorithm_name(row.algorithm), strategy_name(row.strategy), row.points, range,
                row.mean_path_length, 100.0 * row.resolved_rate, row.mean_stops,
                row.mean_lower_bound, row.mean_bound_ratio, row.mean_pairwise_bound,
                row.mean_pairwise_ratio, row.mean_hypotheses, row.mean_stop_ms);
  }
}

EngineDisambiguationOptions engine_loop_options(const DisambiguationEvalArgs& args,
                                                const EngineLoopInputs& inputs,
                                                std::uint64_t seed) {
  const DisambiguationProtocolOptions protocol = protocol_options(args, seed);
  EngineDisambiguationOptions options;
  options.trials = inputs.trials;
  options.seed = seed;
  options.loop.laser.enabled = args.sensor == "laser";
  options.loop.laser.max_range = inputs.laser_max_range;
  options.loop.laser.sigma_m = inputs.laser_sigma_m;
  options.loop.laser.beams = inputs.laser_beams;
  options.loop.planner.algorithm = protocol.algorithms.front();
  options.loop.planner.strategy = protocol.strategies.front();
  options.loop.planner.points = protocol.points.front();
  return options;
}

nlohmann::json engine_loop_json(const DisambiguationEvalArgs& args,
                                const EngineDisambiguationOptions& options,
                                const std::vector<EngineDisambiguationResult>& results) {
  nlohmann::json rows = nlohmann::json::array();
  for (const EngineDisambiguationResult& row : results) {
    rows.push_back(
        {{"map", row.map},
         {"algorithm", algorithm_name(options.loop.planner.algorithm)},
         {"strategy", strategy_name(options.loop.planner.strategy)},
         {"points", options.loop.planner.points},
         {"trials", row.trials},
         {"drawn", row.drawn},
         {"truth_seeded", row.truth_seeded},
         {"true_survived_rate", number_or_null(row.true_survived_rate)},
         {"wrong_answers", row.wrong_answers},
         {"errors", row.errors},
         {"resolved_rate", number_or_null(row.resolved_rate)},
         {"mean_hypotheses", number_or_null(row.mean_hypotheses)},
         {"mean_path_length", number_or_null(row.mean_path_length)},
         {"mean_noise_free_path_length", number_or_null(row.mean_noise_free_path_length)},
         {"noise_free_resolved_rate", number_or_null(row.noise_free_resolved_rate)},
         {"mean_stops", number_or_null(row.mean_stops)},
         {"median_ms", number_or_null(row.median_ms)}});
  }
  return {{"protocol", "disambiguation"}, {"sensor", args.sensor}, {"configurations", rows}};
}

void print_engine_loop_table(const DisambiguationEvalArgs& args,
                             const EngineDisambiguationOptions& options,
                             const std::vector<EngineDisambiguationResult>& results) {
  std::printf("Seed 002 with the engine in the loop: %s, %s %s, %d points; ambiguous starts\n",
              args.sensor.c_str(), algorithm_name(options.loop.planner.algorithm),
              strategy_name(options.loop.planner.strategy), options.loop.planner.points);
  std::printf("%-22s %6s %6s %6s %9s %6s %9s %7s %10s %6s %9s\n", "map", "trials", "drawn", "hyps",
              "survived", "wrong", "resolved", "path", "noise-free", "stops", "median ms");
  for (const EngineDisambiguationResult& row : results) {
    std::printf("%-22.22s %6d %6d %6.2f %8.1f%% %6d %8.1f%% %7.2f %10.2f %6.2f %9.1f\n",
                row.map.c_str(), row.trials, row.drawn, row.mean_hypotheses,
                100.0 * row.true_survived_rate, row.wrong_answers, 100.0 * row.resolved_rate,
                row.mean_path_length, row.mean_noise_free_path_length, row.mean_stops,
                row.median_ms);
  }
}

}  // namespace

void run_engine_loop_eval(const DisambiguationEvalArgs& args, const EngineLoopInputs& inputs,
                          std::uint64_t seed, bool json, bool quiet) {
  const EngineDisambiguationOptions options = engine_loop_options(args, inputs, seed);
  std::vector<EvalMap> maps;
  for (const std::string& file : inputs.map_files)
    maps.push_back({file, load_map(file, {}, "--maps")});
  const SonarRing ring = load_sonar_ring(input_path(inputs.ring, "--ring"), limits());
  const std::vector<EngineDisambiguationResult> results = run_engine_disambiguation(
      maps, ring, options, progress_line("eval disambiguation --sensor", "trials", quiet));
  if (json) {
    std::cout << engine_loop_json(args, options, results).dump(2) << "\n";
    return;
  }
  print_engine_loop_table(args, options, results);
}

void add_disambiguation_options(CLI::App* cmd, DisambiguationEvalArgs& args, bool old_spelling) {
  const std::string note = old_spelling ? "--protocol disambiguation: " : "";
  cmd->add_option("--environments", args.environments, note + "random offices (seeds 1..N)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--starts", args.starts, note + "ambiguous starts per office")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--repeats", args.repeats, note + "runs per start (seeds of the points)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--points", args.points, note + "comma-separated random points per round")
      ->delimiter(',')
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--range", args.ranges,
                  note + "comma-separated sensor ranges in cell units, inf for unlimited")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--algorithms", args.algorithms, note + "comma-separated: col, ual")
      ->delimiter(',')
      ->check(CLI::IsMember({"col", "ual"}))
      ->capture_default_str();
  const std::string engine_loop =
      "sonar | laser: the engine in the loop on --maps (default room_symmetric, "
      "apartment_small), --trials ambiguous starts each, noisy sensing and odometry";
  if (old_spelling) {
    cmd->add_option("--sensor", args.sensor,
                    note + engine_loop + "; --protocol team: ir (default) | laser | sonar")
        ->check(CLI::IsMember({"sonar", "laser", "ir"}));
  } else {
    cmd->add_option("--sensor", args.sensor, engine_loop)->check(CLI::IsMember({"sonar", "laser"}));
  }
  cmd->add_option("--strategies", args.strategies,
                  note + "comma-separated: weighted, hybrid (seed 002 §V-A)")
      ->delimiter(',')
      ->check(CLI::IsMember({"weighted", "hybrid"}))
      ->capture_default_str();
}

void run_disambiguation_eval(const DisambiguationEvalArgs& args, std::uint64_t seed, bool json,
                             bool quiet) {
  const DisambiguationProtocolOptions options = protocol_options(args, seed);
  const DisambiguationProtocolResult result =
      run_disambiguation_protocol(options, progress_line("eval disambiguation", "trials", quiet));
  if (json) {
    std::cout << result_json(result).dump(2) << "\n";
    return;
  }
  print_table(args, result);
}

}  // namespace gridloc::cli
