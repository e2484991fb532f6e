// gridloc simulate: sonar readings at a pose on a map, as a readings JSON file.
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "options.hpp"

namespace gridloc::cli {
namespace {

struct SimulateArgs {
  std::string map, ring, pose, out;
  bool realistic = false;
  int firings = 1;
  SonarSimOptions sim;
  OctomapArgs octomap;
};

void run(const SimulateArgs& a) {
  const Pose2 pose = parse_pose(a.pose, "--pose");
  SonarSimOptions o = a.sim;
  if (a.realistic) o = SonarSimOptions::realistic(a.sim.seed);
  if (a.firings < 1 || a.firings > 100) {
    throw Error("--firings must lie in [1, 100], got " + std::to_string(a.firings));
  }
  const OccupancyMap map = load_map(a.map, a.octomap.slice);
  const SonarRing ring = load_sonar_ring(a.ring);
  // Consecutive firings from the same pose draw their noise independently: the first from
  // --seed (what one firing would read), the others from seeds hashed from it and k, so
  // that neighbouring --seed values share no firing.
  std::vector<std::vector<double>> firings;
  for (int k = 0; k < a.firings; ++k) {
    SonarSimOptions firing = o;
    if (k > 0)
      firing.seed = Rng(o.seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(k))).next();
    firings.push_back(simulate_sonar(map, ring, pose, firing));
  }
  nlohmann::json j = {{"pose", to_json(pose)}, {"ranges_m", firings.front()}};
  if (a.firings > 1) j["firings_m"] = firings;
  if (a.out.empty()) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::ofstream f(a.out);
  if (!f) throw Error(a.out + ": cannot write the readings file");
  f << j.dump(2) << "\n";
}

}  // namespace

void add_simulate(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  a->ring = data_dir() + "/sensors/wheelchair_14.yaml";
  auto* cmd = app.add_subcommand("simulate", "Simulate sonar readings at a pose; prints JSON");
  cmd->add_option("--map", a->map, "map_server YAML (or OctoMap .bt/.ot)")->required();
  a->octomap.add_to(cmd);
  cmd->add_option("--ring", a->ring, "sonar ring YAML")->capture_default_str();
  cmd->add_option("--pose", a->pose, "robot pose x,y,theta (m, m, rad)")->required();
  cmd->add_option("--out", a->out, "write the readings here instead of stdout");
  cmd->add_option("--seed", a->sim.seed, "noise seed")->capture_default_str();
  cmd->add_option("--sigma", a->sim.range_sigma_m, "Gaussian range noise (m)")
      ->capture_default_str();
  cmd->add_option("--sigma-frac", a->sim.range_sigma_frac, "range noise, fraction of the range")
      ->capture_default_str();
  cmd->add_option("--dropout", a->sim.dropout_prob, "probability of no echo")
      ->capture_default_str();
  cmd->add_option("--specular-deg", a->sim.specular_incidence_deg,
                  "no echo beyond this incidence angle (90 = off)")
      ->capture_default_str();
  cmd->add_option("--crosstalk", a->sim.crosstalk_prob, "probability of a wrong short echo")
      ->capture_default_str();
  cmd->add_option("--firings", a->firings,
                  "consecutive firings from the pose (> 1: written as firings_m, which "
                  "localize filters for crosstalk)")
      ->capture_default_str();
  cmd->add_flag("--realistic", a->realistic,
                "use the evaluation's realistic noise (overrides the noise options)");
  cmd->callback([a] { run(*a); });
}

}  // namespace gridloc::cli
