#pragma once
// gridloc eval --protocol disambiguation (issue 15): seed 002's protocol on random offices,
// COL and UAL with the standard weighted and hybrid strategies, by points and range, with the
// lower bound beside every mean.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace gridloc::cli {

struct DisambiguationEvalArgs {
  int environments = 20, starts = 3, repeats = 2;
  std::vector<int> points = {1, 5, 10, 40, 80, 250, 500};
  std::vector<std::string> ranges = {"inf", "5", "2", "0.9"};
  std::vector<std::string> algorithms = {"col", "ual"};
  std::vector<std::string> strategies = {"weighted", "hybrid"};
  std::string sensor;  ///< sonar | laser: the engine-in-the-loop variant on --maps
};

/// The engine-in-the-loop variant's inputs from gridloc eval's own options.
struct EngineLoopInputs {
  std::vector<std::string> map_files;  ///< occupancy maps
  std::string ring;                    ///< sonar ring YAML
  int trials = 100;                    ///< ambiguous starts per map
  double laser_max_range = 8.0, laser_sigma_m = 0.01;
  int laser_beams = 360;
};

/// Registers --environments, --starts, --repeats, --points, --range, --algorithms,
/// --strategies and --sensor: on `gridloc eval disambiguation`, or with `old_spelling` on
/// `gridloc eval` (they take effect with --protocol disambiguation; --sensor with --protocol
/// team too).
void add_disambiguation_options(CLI::App* cmd, DisambiguationEvalArgs& args, bool old_spelling);

/// Runs the protocol and prints its table (or JSON with `json`), progress on stderr unless
/// `quiet`.
void run_disambiguation_eval(const DisambiguationEvalArgs& args, std::uint64_t seed, bool json,
                             bool quiet);

/// The engine-in-the-loop variant (--sensor): each map's ambiguous starts, the planner with
/// the first of --algorithms, --strategies and --points.
void run_engine_loop_eval(const DisambiguationEvalArgs& args, const EngineLoopInputs& inputs,
                          std::uint64_t seed, bool json, bool quiet);

}  // namespace gridloc::cli
