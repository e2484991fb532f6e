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
#include "options.hpp"

namespace gridloc::cli {
namespace {

struct DemoArgs {
  std::string map, ring;
  std::uint64_t seed = 7;
  bool json = false;
  OctomapArgs octomap;
};

void run(const DemoArgs& a) {
  const OccupancyMap map = load_map(a.map, a.octomap.slice);
  const SonarRing ring = load_sonar_ring(a.ring);
  Rng rng(a.seed);
  const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
  const auto ranges = simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()));
  SearchWindow window;
  window.center = {
      truth.x + rng.uniform(-window.half_xy, window.half_xy),
      truth.y + rng.uniform(-window.half_xy, window.half_xy),
      normalize_angle(truth.theta + rng.uniform(-window.half_theta, window.half_theta))};
  const CorrelationEstimator estimator(map, ring);
  const Estimate e = estimator.estimate({ranges}, window);
  const double dp = std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
  const double dt = rad2deg(std::abs(normalize_angle(e.pose.theta - truth.theta)));
  const bool success = dp <= 0.10 && dt <= 7.0;

  if (a.json) {
    nlohmann::json j = {{"map", a.map},
                        {"ring", ring.name},
                        {"truth", to_json(truth)},
                        {"prior", to_json(window.center)},
                        {"readings_m", ranges},
                        {"estimate", to_json(e)},
                        {"position_error_m", dp},
                        {"heading_error_deg", dt},
                        {"success", success},
                        {"elapsed_ms", e.stats.elapsed_ms}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  auto line = [](const char* label, const Pose2& p) {
    std::printf("%-9s x = %6.3f m   y = %6.3f m   theta = %7.2f deg\n", label, p.x, p.y,
                rad2deg(p.theta));
  };
  std::printf("gridloc demo: map %s, ring '%s' (%zu sonars), seed %llu\n", a.map.c_str(),
              ring.name.c_str(), ring.sonars.size(), static_cast<unsigned long long>(a.seed));
  line("truth", truth);
  line("prior", window.center);
  line("estimate", e.pose);
  std::printf("error     %.3f m, %.2f deg  -> %s (success: <= 0.10 m and <= 7 deg)\n", dp, dt,
              success ? "success" : "FAILURE");
  std::printf("score     %.3f (normalized %.3f), confidence %.2f -> %s\n", e.score,
              e.normalized_score, e.confidence, to_string(e.verdict).c_str());
  const bool multires = estimator.options().strategy == SearchStrategy::Multires;
  std::printf("time      %.2f ms (%s search, %lld poses scored%s; window +-%.2f m, +-%.0f deg)\n",
              e.stats.elapsed_ms, to_string(estimator.options().strategy).c_str(),
              e.stats.poses_scored,
              multires ? "" : (e.stats.proven_optimal ? ", proven optimal" : ", not proven"),
              window.half_xy, rad2deg(window.half_theta));
}

}  // namespace

void add_demo(CLI::App& app) {
  auto a = std::make_shared<DemoArgs>();
  a->map = data_dir() + "/room_furnished.yaml";
  a->ring = data_dir() + "/sensors/wheelchair_14.yaml";
  auto* cmd = app.add_subcommand("demo", "Simulate, perturb the prior, localize, report");
  cmd->add_option("--map", a->map, "map_server YAML (or OctoMap .bt/.ot)")->capture_default_str();
  a->octomap.add_to(cmd);
  cmd->add_option("--ring", a->ring, "sonar ring YAML")->capture_default_str();
  cmd->add_option("--seed", a->seed, "seed of pose, prior and noise")->capture_default_str();
  cmd->add_flag("--json", a->json, "print JSON instead of text");
  cmd->callback([a] { run(*a); });
}

}  // namespace gridloc::cli
