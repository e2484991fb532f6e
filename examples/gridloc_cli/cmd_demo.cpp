// gridloc demo: the main job on the bundled defaults: simulate the ring at a pose, perturb
// the prior within the seed window, localize, and report.
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

struct DemoArgs {
  std::string map, ring;
  std::uint64_t seed = 7;
  bool json = false;
  OctomapArgs octomap;
};

void run(const DemoArgs& args) {
  const OccupancyMap map = load_map(args.map, args.octomap.slice);
  const SonarRing ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
  Rng rng(args.seed);
  const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
  const auto ranges = simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()));
  SearchWindow window;
  window.center = {
      truth.x + rng.uniform(-window.half_xy, window.half_xy),
      truth.y + rng.uniform(-window.half_xy, window.half_xy),
      normalize_angle(truth.theta + rng.uniform(-window.half_theta, window.half_theta))};
  const CorrelationEstimator estimator(map, ring);
  const Estimate estimate = estimator.estimate({ranges}, window);
  const double position_error_m = std::hypot(estimate.pose.x - truth.x, estimate.pose.y - truth.y);
  const double heading_error_deg =
      rad2deg(std::abs(normalize_angle(estimate.pose.theta - truth.theta)));
  const bool success = position_error_m <= 0.10 && heading_error_deg <= 7.0;

  if (args.json) {
    nlohmann::json out = {{"map", args.map},
                          {"ring", ring.name},
                          {"truth", to_json(truth)},
                          {"prior", to_json(window.center)},
                          {"readings_m", ranges},
                          {"estimate", to_json(estimate)},
                          {"position_error_m", position_error_m},
                          {"heading_error_deg", heading_error_deg},
                          {"success", success},
                          {"elapsed_ms", estimate.stats.elapsed_ms}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  auto line = [](const char* label, const Pose2& p) {
    std::printf("%-9s x = %6.3f m   y = %6.3f m   theta = %7.2f deg\n", label, p.x, p.y,
                rad2deg(p.theta));
  };
  std::printf("gridloc demo: map %s, ring '%s' (%zu sonars), seed %llu\n", args.map.c_str(),
              ring.name.c_str(), ring.sonars.size(), static_cast<unsigned long long>(args.seed));
  line("truth", truth);
  line("prior", window.center);
  line("estimate", estimate.pose);
  std::printf("error     %.3f m, %.2f deg  -> %s (success: <= 0.10 m and <= 7 deg)\n",
              position_error_m, heading_error_deg, success ? "success" : "FAILURE");
  std::printf("score     %.3f (normalized %.3f), confidence %.2f -> %s\n", estimate.score,
              estimate.normalized_score, estimate.confidence, to_string(estimate.verdict).c_str());
  const bool multires = estimator.options().strategy == SearchStrategy::Multires;
  std::printf("time      %.2f ms (%s search, %lld poses scored%s; window +-%.2f m, +-%.0f deg)\n",
              estimate.stats.elapsed_ms, to_string(estimator.options().strategy).c_str(),
              estimate.stats.poses_scored,
              multires ? "" : (estimate.stats.proven_optimal ? ", proven optimal" : ", not proven"),
              window.half_xy, rad2deg(window.half_theta));
}

}  // namespace

void add_demo(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  args->map = data_dir() + "/room_furnished.yaml";
  args->ring = data_dir() + "/sensors/wheelchair_14.yaml";
  auto* cmd = app.add_subcommand("demo", "Simulate, perturb the prior, localize, report");
  cmd->add_option("--map", args->map,
                  "map_server YAML (or OctoMap .bt/.ot) (- reads standard input)")
      ->capture_default_str();
  args->octomap.add_to(cmd);
  cmd->add_option("--ring", args->ring, "sonar ring YAML (- reads standard input)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of pose, prior and noise")->capture_default_str();
  cmd->add_flag("--json", args->json, "print JSON instead of text");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--ring"}});
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
