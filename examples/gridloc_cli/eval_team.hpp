#pragma once
// gridloc eval --protocol team (issue 16): random teams of each size on each map, every robot
// clear of the walls and seeing a corner or wall, linked robots within the camera's range
// with a line of sight; the unique-and-correct rate by team size.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace gridloc::cli {

struct TeamEvalArgs {
  std::vector<int> robots = {1, 2, 3, 4};
};

/// What the team protocol takes from gridloc eval's own options.
struct TeamEvalInputs {
  std::vector<std::string> map_files;
  std::string sensor = "ir";  ///< ir | laser | sonar
  std::string ring;           ///< sonar ring YAML
  int trials = 100;
  double laser_max_range = 8.0, laser_sigma_m = 0.01;
  int laser_beams = 360;
};

/// Registers --robots: on `gridloc eval team`, or with `old_spelling` on `gridloc eval` (it
/// takes effect with --protocol team).
void add_team_options(CLI::App* cmd, TeamEvalArgs& args, bool old_spelling);

/// Runs the protocol and prints its table (or JSON), progress on stderr unless `quiet`.
void run_team_eval(const TeamEvalArgs& args, const TeamEvalInputs& inputs, std::uint64_t seed,
                   bool json, bool quiet);

}  // namespace gridloc::cli
