// gridloc simulate: sonar readings at a pose on a map, as a readings JSON file.
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "limit_options.hpp"
#include "old_spelling.hpp"
#include "options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

struct SimulateArgs {
  std::string map, ring, pose, out;
  bool realistic = false;
  int firings = 1;
  bool scan = false;  ///< a laser scan (CSV) instead of sonar readings
  int beams = 360;
  double max_range = 20.0;
  SonarSimOptions sim;
  OctomapArgs octomap;
};

/// A laser scan at the pose, as `angle_rad,range_m` lines (what `localize --scan` reads).
std::string scan_csv(const SimulateArgs& args, const OccupancyMap& map, const Pose2& pose) {
  require_flag(args.beams >= 1 && args.beams <= 100000, "--beams", args.beams,
               "must lie in [1, 100000]");
  const RangeScan scan =
      simulate_scan(map, pose, args.beams, args.max_range, args.sim.range_sigma_m, args.sim.seed);
  std::ostringstream csv;
  csv.precision(9);
  csv << "# gridloc simulate --scan at " << pose.x << "," << pose.y << "," << pose.theta
      << "; a range of " << args.max_range << " is no return\n";
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    csv << scan.angles[i] << "," << scan.ranges[i] << "\n";
  }
  return csv.str();
}

void write(const std::string& text, const std::string& path) {
  if (path.empty()) {
    std::cout << text;
    return;
  }
  std::ofstream file(path);
  if (!file) throw Error(path + ": cannot write the readings file");
  file << text;
}

void run(const SimulateArgs& args) {
  const Pose2 pose = parse_pose(args.pose, "--pose");
  if (args.scan) {
    write(scan_csv(args, load_map(args.map, args.octomap.slice), pose), args.out);
    return;
  }
  SonarSimOptions options = args.sim;
  if (args.realistic) options = SonarSimOptions::realistic(args.sim.seed);
  require_flag(args.firings >= 1 && args.firings <= 100, "--firings", args.firings,
               "must lie in [1, 100]");
  const OccupancyMap map = load_map(args.map, args.octomap.slice);
  const SonarRing ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
  // Consecutive firings from the same pose draw their noise independently: the first from
  // --seed (what one firing would read), the others from seeds hashed from it and k, so
  // that neighbouring --seed values share no firing.
  std::vector<std::vector<double>> firings;
  for (int k = 0; k < args.firings; ++k) {
    SonarSimOptions firing = options;
    if (k > 0)
      firing.seed =
          Rng(options.seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(k))).next();
    firings.push_back(simulate_sonar(map, ring, pose, firing));
  }
  nlohmann::json out = {{"pose", to_json(pose)}, {"ranges_m", firings.front()}};
  if (args.firings > 1) out["firings_m"] = firings;
  write(out.dump(2) + "\n", args.out);
}

}  // namespace

void add_simulate(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  args->ring = data_dir() + "/sensors/wheelchair_14.yaml";
  auto* cmd = app.add_subcommand("simulate", "Simulate sonar readings at a pose; prints JSON");
  cmd->add_option("--map", args->map,
                  "map_server YAML (or OctoMap .bt/.ot) (- reads standard input)")
      ->required();
  args->octomap.add_to(cmd);
  cmd->add_option("--ring", args->ring, "sonar ring YAML (- reads standard input)")
      ->capture_default_str();
  cmd->add_option("--pose", args->pose, "robot pose x,y,theta (m, m, rad)")->required();
  // --out is the old spelling (kept, out of --help): --out names a folder elsewhere.
  cmd->add_option("--readings-out", args->out,
                  "write the readings JSON (with --scan, the scan CSV) to this file instead of "
                  "stdout");
  cmd->add_option("--out", args->out, "old spelling of --readings-out")->group(kOldSpelling);
  hide_old_spellings(cmd);
  cmd->add_option("--seed", args->sim.seed, "noise seed")->capture_default_str();
  cmd->add_option("--sigma", args->sim.range_sigma_m, "Gaussian range noise (m)")
      ->capture_default_str();
  cmd->add_option("--sigma-frac", args->sim.range_sigma_frac, "range noise, fraction of the range")
      ->capture_default_str();
  cmd->add_option("--dropout", args->sim.dropout_prob, "probability of no echo")
      ->capture_default_str();
  cmd->add_option("--specular-deg", args->sim.specular_incidence_deg,
                  "no echo beyond this incidence angle (90 = off)")
      ->capture_default_str();
  cmd->add_option("--crosstalk", args->sim.crosstalk_prob, "probability of a wrong short echo")
      ->capture_default_str();
  cmd->add_option("--firings", args->firings,
                  "consecutive firings from the pose (> 1: written as firings_m, which "
                  "localize filters for crosstalk)")
      ->capture_default_str();
  cmd->add_flag("--scan", args->scan,
                "a laser scan instead: angle_rad,range_m lines (CSV, what localize --scan "
                "reads), --beams over a full turn, --sigma noise, --seed");
  cmd->add_option("--beams", args->beams, "--scan: beams over the full turn")
      ->capture_default_str();
  cmd->add_option("--max-range", args->max_range, "--scan: max range (m); no return reads this")
      ->capture_default_str();
  cmd->add_flag("--realistic", args->realistic,
                "use the evaluation's realistic noise (overrides the noise options)");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--ring"}});
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
