#pragma once
// gridloc disambiguate's arguments and JSON, shared by its polygon-map path (seed 002 as the
// paper has it, cmd_disambiguate.cpp) and its occupancy-map path (the engine in the loop,
// disambiguate_grid.cpp).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/range_view.hpp"

namespace gridloc::cli {

struct DisambiguateArgs {
  std::string map, scan, readings, pose, out, algorithm = "ual", strategy = "hybrid";
  std::string ring, sensor = "sonar";
  double range = kUnlimitedRange;
  double max_range = 8.0;  ///< a scan CSV's max range, and the simulated laser's
  int points = MinimumDistanceOptions{}.points;
  int threads = 1;
  std::uint64_t seed = 1;
  bool rotation = false, json = false;
};

/// The planner's options from the command line.
MinimumDistanceOptions planner_options(const DisambiguateArgs& args);

/// The plan as the command prints it: hypotheses, the path in the start frame and in each
/// standing hypothesis's world frame, its length, the stops, what each ruled out, whether
/// one remains and whether it is the truth (`true_index`, -1: unknown, then null).
nlohmann::json plan_json(const MinimumDistancePlan& plan, int true_index);

/// Creates --out (when given); gridloc::Error when it cannot.
void make_out_dir(const std::string& out);

/// Writes `out` as DIR/disambiguation.json.
void write_plan_json(const std::string& out_dir, const nlohmann::json& out);

}  // namespace gridloc::cli
