#include "eval_team.hpp"

#include "eval_disambiguation.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "gridloc/engine/evaluation/team_protocol.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "progress.hpp"
#include "stdin_input.hpp"
#include "team_io.hpp"

namespace gridloc::cli {

namespace {

namespace fs = std::filesystem;

TeamSensing sensing_from(const TeamEvalInputs& inputs) {
  TeamSensing sensing;
  sensing.sensor = parse_team_sensor(inputs.sensor);
  sensing.laser_beams = inputs.laser_beams;
  sensing.laser_range_m = inputs.laser_max_range;
  sensing.laser_sigma_m = inputs.laser_sigma_m;
  if (sensing.sensor == TeamSensor::Sonar)
    sensing.ring = load_sonar_ring(input_path(inputs.ring, "--ring"), limits());
  return sensing;
}

TeamProtocolOptions protocol_options(const TeamEvalArgs& args, const TeamEvalInputs& inputs,
                                     const TeamSensing& sensing, std::uint64_t seed) {
  TeamProtocolOptions options;
  options.robots = args.robots;
  options.trials = inputs.trials;
  options.seed = seed;
  options.team = solver_options(sensing);
  return options;
}

nlohmann::json configuration_json(const TeamConfiguration& c) {
  return {{"robots", c.robots},
          {"trials", c.trials},
          {"unique_correct_rate", c.unique_correct_rate},
          {"ambiguous_rate", c.ambiguous_rate},
          {"not_localized_rate", c.not_localized_rate},
          {"wrong_localized", c.wrong_localized},
          {"mean_position_error_m", c.mean_position_error_m},
          {"mean_heading_error_deg", c.mean_heading_error_deg},
          {"median_ms", c.median_ms}};
}

nlohmann::json report_json(const TeamEvalInputs& inputs, const TeamProtocolReport& report) {
  nlohmann::json overall = nlohmann::json::array(), per_map = nlohmann::json::array();
  for (const auto& c : report.overall) overall.push_back(configuration_json(c));
  for (std::size_t m = 0; m < report.per_world.size(); ++m)
    for (const auto& c : report.per_world[m]) {
      nlohmann::json row = configuration_json(c);
      row["map"] = fs::path(inputs.map_files[m]).stem().string();
      per_map.push_back(row);
    }
  return {{"protocol", "team"},
          {"sensor", inputs.sensor},
          {"trials", inputs.trials},
          {"configurations", overall},
          {"per_map", per_map}};
}

void print_row(const std::string& map, const TeamConfiguration& c) {
  std::printf("%-16s %6d %6d %14.1f %10.1f %8.1f %6d %10.3f %10.2f %9.2f\n", map.c_str(), c.robots,
              c.trials, 100.0 * c.unique_correct_rate, 100.0 * c.ambiguous_rate,
              100.0 * c.not_localized_rate, c.wrong_localized, c.mean_position_error_m,
              c.mean_heading_error_deg, c.median_ms);
}

void print_table(const TeamEvalInputs& inputs, const TeamProtocolReport& report) {
  std::printf("team protocol, sensor %s, %d trials per team size and map\n", inputs.sensor.c_str(),
              inputs.trials);
  std::printf("%-16s %6s %6s %14s %10s %8s %6s %10s %10s %9s\n", "map", "robots", "trials",
              "unique+ok %", "ambig %", "none %", "wrong", "pos err m", "head err", "median ms");
  for (std::size_t m = 0; m < report.per_world.size(); ++m)
    for (const auto& c : report.per_world[m])
      print_row(fs::path(inputs.map_files[m]).stem().string(), c);
  for (const auto& c : report.overall) print_row("all", c);
}

}  // namespace

void add_team_options(CLI::App* cmd, TeamEvalArgs& args, bool old_spelling) {
  cmd->add_option("--robots", args.robots,
                  std::string(old_spelling ? "--protocol team: " : "") +
                      "comma-separated team sizes (each in 1..16)")
      ->delimiter(',')
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
}

void run_team_eval(const TeamEvalArgs& args, const TeamEvalInputs& inputs, std::uint64_t seed,
                   bool json, bool quiet) {
  const TeamSensing sensing = sensing_from(inputs);
  std::vector<TeamWorld> worlds;
  for (const std::string& file : inputs.map_files)
    worlds.push_back(load_team_world(file, "--maps"));
  std::vector<std::unique_ptr<TeamSimulator>> simulators;
  std::vector<const TeamSimulator*> pointers;
  for (const TeamWorld& world : worlds) {
    simulators.push_back(std::make_unique<TeamSimulator>(world, sensing));
    pointers.push_back(simulators.back().get());
  }
  const TeamProtocolReport report =
      run_team_protocol(pointers, protocol_options(args, inputs, sensing, seed),
                        progress_line("eval team", "trials", quiet));
  if (json) {
    std::cout << report_json(inputs, report).dump(2) << "\n";
    return;
  }
  print_table(inputs, report);
}

}  // namespace gridloc::cli
