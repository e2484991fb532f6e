// gridloc team: several robots localized together through the virtual links between them
// (seed 003): each robot's candidate placements from its own sensing, the pairs the links
// join, the team's solutions and a verdict for the team and each robot.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>

#include "commands.hpp"
#include "gridloc/engine/team/team_sensing.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "output_files.hpp"
#include "plot.hpp"
#include "stdin_input.hpp"
#include "team_io.hpp"
#include "team_render.hpp"
#include "team_simulated.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = std::numbers::pi / 180.0;

struct TeamArgs {
  std::string map, robots, poses, sensor = "ir", ring, link_noise = "0.02,1", out;
  double link_range = CameraModel{}.max_range_m;
  double ir_range = IrSensorOptions{}.max_range_m;
  std::uint64_t seed = 1;
  bool json = false, exact = false;
};

TeamSensing sensing_from(const TeamArgs& args) {
  TeamSensing sensing;
  sensing.sensor = parse_team_sensor(args.sensor);
  sensing.ir.max_range_m = args.ir_range;
  sensing.camera.max_range_m = args.link_range;
  parse_link_noise(args.link_noise, sensing.camera);
  sensing.noise = !args.exact;
  if (sensing.sensor == TeamSensor::Sonar) {
    if (args.ring.empty()) throw Error("team --sensor sonar: give the ring with --ring");
    sensing.ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
  }
  return sensing;
}

TeamCase team_from(const TeamArgs& args, TeamCandidates candidates,
                   const TeamSimulation& simulation) {
  if (args.poses.empty() == args.robots.empty())
    throw Error("team: give either --poses (simulated) or --robots robots.json (measured)");
  if (!args.poses.empty())
    return simulation.simulate(std::move(candidates), parse_team_poses(args.poses), args.seed);
  return load_team(args.robots, candidates);
}

void print_summary(const TeamCase& team, const TeamAnswer& answer) {
  for (std::size_t r = 0; r < team.robots.size(); ++r) {
    const RobotAnswer& robot = answer.robots[r];
    std::printf("robot %zu: %zu candidates, %s", r, team.robots[r].candidates.size(),
                to_string(robot.verdict).c_str());
    if (!answer.solutions.empty())
      std::printf(" at (%.3f, %.3f, %.1f deg)", robot.pose.x, robot.pose.y,
                  robot.pose.theta / kDeg);
    if (robot.places.size() > 1) std::printf(", %zu places", robot.places.size());
    std::printf("\n");
  }
  std::printf("team: %s, %zu solution%s, %zu links used\n", to_string(answer.verdict).c_str(),
              answer.solutions.size(), answer.solutions.size() == 1 ? "" : "s",
              answer.links_used.size());
}

TeamPicture picture_of(const TeamArgs& args, const TeamWorld& world, const TeamCase& team,
                       const TeamAnswer& answer) {
  TeamPicture picture;
  picture.title = fs::path(args.map).filename().string() + ": " +
                  std::to_string(team.robots.size()) + " robots, " + args.sensor +
                  ", links up to " + plot::number(args.link_range) + " m";
  picture.caption = "team " + to_string(answer.verdict) + ", " +
                    std::to_string(answer.solutions.size()) + " solution" +
                    (answer.solutions.size() == 1 ? "" : "s");
  picture.polygons = world.polygons;
  picture.grid = world.grid;
  picture.features = world.features;
  for (const TeamRobot& robot : team.robots) picture.candidates.push_back(robot.candidates);
  picture.solutions = answer.solutions;
  picture.links = team.links;
  picture.links_used = answer.links_used;
  picture.truth = team.truth;
  return picture;
}

void write_outputs(const TeamArgs& args, const TeamWorld& world, const TeamCase& team,
                   const TeamAnswer& answer, const nlohmann::json& out) {
  const fs::path folder = output_folder(args.out);
  const std::string json_path = (folder / "team.json").string();
  const std::string png_path = (folder / "team.png").string();
  write_json_file(json_path, out, "the team's answer");
  plot::write_png(png_path, render_team(picture_of(args, world, team, answer)));
  if (!args.json) std::printf("wrote %s and %s\n", png_path.c_str(), json_path.c_str());
}

void run(const TeamArgs& args, const TeamSimulation& simulation) {
  const TeamWorld world = load_team_world(args.map);
  const TeamSensing sensing = sensing_from(args);
  const TeamCase team = team_from(args, TeamCandidates(world, sensing), simulation);
  const TeamAnswer answer =
      localize_team(team.robots, team.links, world.features, solver_options(sensing));
  nlohmann::json out = team_json(team, answer);
  if (!team.truth.empty()) out["correct"] = simulation.correct(answer, team.truth);
  if (args.json)
    std::cout << out.dump(2) << "\n";
  else
    print_summary(team, answer);
  if (!args.out.empty()) write_outputs(args, world, team, answer, out);
}

}  // namespace

void add_team(CLI::App& app, const TeamSimulation& simulation) {
  auto args = std::make_shared<TeamArgs>();
  auto* cmd = app.add_subcommand(
      "team", "Localize several robots together through the virtual links between them (seed 003)");
  cmd->add_option("--map", args->map,
                  "polygon map (YAML with a 'boundary') or occupancy map (map_server YAML) (- "
                  "reads standard input)")
      ->required();
  cmd->add_option("--robots", args->robots,
                  "robots.json: each robot's scan (or sonar readings) and the measured links (- "
                  "reads standard input)");
  cmd->add_option("--poses", args->poses,
                  "true poses \"x,y,theta;x,y,theta[;...]\" (m, m, theta in radians): each robot's "
                  "scan and the links are simulated there");
  cmd->add_option("--sensor", args->sensor,
                  "ir (the rotating IR sensor and its features, seed 003), laser or sonar (the "
                  "correlation engine's hypotheses)")
      ->check(CLI::IsMember({"ir", "laser", "sonar"}));
  cmd->add_option("--ring", args->ring, "sonar ring YAML (--sensor sonar; - reads standard input)");
  cmd->add_option("--ir-range", args->ir_range,
                  "the IR sensor's truncation range (m); the thesis truncated at 0.30")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--link-range", args->link_range,
                  "the camera's range for links (m); the thesis's CMUCam: about 1.1")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--link-noise", args->link_noise,
                  "SIGMA_M[,BEARING_DEG]: link length sigma at the link range (growing with the "
                  "square of the length) and bearing sigma");
  cmd->add_flag("--exact", args->exact, "--poses: simulate without sensor and link noise");
  cmd->add_option("--seed", args->seed, "seed of the simulated noise");
  cmd->add_option("--out", args->out, "folder for team.png and team.json");
  cmd->add_flag("--json", args->json, "print the answer as JSON");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--robots"}, {"--ring"}});
  cmd->callback([args, simulation] { run(*args, simulation); });
}

}  // namespace gridloc::cli
