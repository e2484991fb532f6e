#pragma once
// gridloc eval --protocol disambiguation (issue 15): seed 002's protocol on random offices,
// COL and UAL with the standard weighted and hybrid strategies, by points and range, with the
// lower bound beside every mean.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace gridloc::cli {

struct DisambiguationEvalArgs {
  int environments = 20, starts = 3, repeats = 2;
  std::vector<int> points = {1, 5, 10, 40, 80, 250, 500};
  std::vector<std::string> ranges = {"inf", "5", "2", "0.9"};
  std::vector<std::string> algorithms = {"col", "ual"};
  std::vector<std::string> strategies = {"weighted", "hybrid"};
};

/// Registers --environments, --starts, --repeats, --points, --range, --algorithms, --strategies
/// (they take effect with --protocol disambiguation).
void add_disambiguation_options(CLI::App* cmd, DisambiguationEvalArgs& args);

/// Runs the protocol and prints its table (or JSON with `json`), progress on stderr unless
/// `quiet`.
void run_disambiguation_eval(const DisambiguationEvalArgs& args, std::uint64_t seed, bool json,
                             bool quiet);

}  // namespace gridloc::cli
