#include "eval_disambiguation.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "gridloc/engine/evaluation/disambiguation_protocol.hpp"
#include "gridloc/grids/error.hpp"

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
                    {"mean_path_length", row.mean_path_length},
                    {"resolved_rate", row.resolved_rate},
                    {"mean_stops", row.mean_stops},
                    {"mean_lower_bound", row.mean_lower_bound},
                    {"mean_bound_ratio", row.mean_bound_ratio},
                    {"mean_hypotheses", row.mean_hypotheses},
                    {"median_ms", row.median_ms},
                    {"mean_stop_ms", row.mean_stop_ms}});
  }
  return {{"protocol", "disambiguation"}, {"trials", result.trials}, {"configurations", rows}};
}

void print_table(const DisambiguationEvalArgs& args, const DisambiguationProtocolResult& result) {
  std::printf(
      "Seed 002 protocol: %d offices x %d starts x %d repeats = %d trials per configuration\n",
      args.environments, args.starts, args.repeats, result.trials);
  std::printf("%-4s %-9s %6s %6s %9s %8s %6s %9s %7s %6s %9s\n", "alg", "strategy", "points",
              "range", "path", "resolved", "stops", "bound", "ratio", "hyps", "ms/stop");
  for (const DisambiguationConfiguration& row : result.configurations) {
    const std::string range = std::isfinite(row.range) ? std::to_string(row.range) : "inf";
    std::printf("%-4s %-9s %6d %6.6s %9.3f %7.1f%% %6.2f %9.3f %7.2f %6.1f %9.2f\n",
                algorithm_name(row.algorithm), strategy_name(row.strategy), row.points,
                range.c_str(), row.mean_path_length, 100.0 * row.resolved_rate, row.mean_stops,
                row.mean_lower_bound, row.mean_bound_ratio, row.mean_hypotheses, row.mean_stop_ms);
  }
}

}  // namespace

void add_disambiguation_options(CLI::App* cmd, DisambiguationEvalArgs& args) {
  const std::string note = "--protocol disambiguation: ";
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
  cmd->add_option("--strategies", args.strategies,
                  note + "comma-separated: weighted, hybrid (seed 002 §V-A)")
      ->delimiter(',')
      ->check(CLI::IsMember({"weighted", "hybrid"}))
      ->capture_default_str();
}

void run_disambiguation_eval(const DisambiguationEvalArgs& args, std::uint64_t seed, bool json,
                             bool quiet) {
  const DisambiguationProtocolOptions options = protocol_options(args, seed);
  const bool terminal = isatty(fileno(stderr)) != 0;
  int last_percent = -1;
  const DisambiguationProtocolResult result =
      run_disambiguation_protocol(options, [&](int done, int total) {
        if (quiet) return;
        const int percent = 100 * done / total;
        if (terminal) {
          std::fprintf(stderr, "\r[eval disambiguation] %d/%d trials", done, total);
          if (done == total) std::fprintf(stderr, "\n");
        } else if (percent / 10 != last_percent / 10) {
          std::fprintf(stderr, "[eval disambiguation] %d/%d trials\n", done, total);
        }
        last_percent = percent;
      });
  if (json) {
    std::cout << result_json(result).dump(2) << "\n";
    return;
  }
  print_table(args, result);
}

}  // namespace gridloc::cli
