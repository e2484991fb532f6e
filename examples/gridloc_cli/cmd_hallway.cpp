// gridloc hallway: seed 004 §4's simulation of robust ICP, repeated over seeds: a 720-point
// scan of the hallway at the origin and one after a motion of 0.5 m, -0.2 m, 20 deg, with
// range noise and outliers; the errors and iterations as the seed reports them.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "gridloc/engine/evaluation/hallway_trials.hpp"

namespace gridloc::cli {
namespace {

struct HallwayArgs {
  int seeds = 100;
  double noise_m = 0.0;
  std::string outliers = "none";
  double share = 0.3;
  bool least_squares = false;
  double success_xy = 0.0;   // 0: 1 mm without noise, 3 cm with
  double success_deg = 0.0;  // 0: 0.01 deg without noise, 0.3 deg with
  bool json = false;
};

void run(const HallwayArgs& args) {
  HallwayTrialsOptions options;
  options.seeds = args.seeds;
  options.noise_m = args.noise_m;
  options.outliers = parse_outlier_kind(args.outliers);
  options.share = args.share;
  options.icp.robust = !args.least_squares;
  options.success_xy =
      args.success_xy > 0.0 ? args.success_xy : (args.noise_m > 0.0 ? 0.03 : 0.001);
  options.success_deg =
      args.success_deg > 0.0 ? args.success_deg : (args.noise_m > 0.0 ? 0.3 : 0.01);
  const HallwayReport report = run_hallway_trials(options);
  const nlohmann::json out = {
      {"seeds", report.seeds},
      {"noise_m", options.noise_m},
      {"outliers", to_string(options.outliers)},
      {"share", options.outliers == OutlierKind::None ? 0.0 : options.share},
      {"estimator", args.least_squares ? "least squares" : "huber"},
      {"success_xy_m", options.success_xy},
      {"success_deg", options.success_deg},
      {"successes", report.successes},
      {"converged", report.converged},
      {"mean_error_x_mm", 1000.0 * report.mean_error_x_m},
      {"mean_error_y_mm", 1000.0 * report.mean_error_y_m},
      {"mean_error_deg", report.mean_error_deg},
      {"mean_iterations", report.mean_iterations}};
  if (args.json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf(
      "seed 004 hallway, %d seeds, %.3f m noise, outliers %s: %d within %.3f m and %.2f deg "
      "(%d converged); over those, mean errors %.2f mm, %.2f mm, %.3f deg, %.1f iterations\n",
      report.seeds, options.noise_m, to_string(options.outliers).c_str(), report.successes,
      options.success_xy, options.success_deg, report.converged, 1000.0 * report.mean_error_x_m,
      1000.0 * report.mean_error_y_m, report.mean_error_deg, report.mean_iterations);
}

}  // namespace

void add_hallway(CLI::App& app) {
  auto args = std::make_shared<HallwayArgs>();
  auto* cmd = app.add_subcommand(
      "hallway", "Seed 004's robust ICP simulation over seeds: errors and iterations");
  cmd->add_option("--seeds", args->seeds, "runs (seeds 1..N)")->capture_default_str();
  cmd->add_option("--noise", args->noise_m, "Gaussian range noise on both scans (m)")
      ->capture_default_str();
  cmd->add_option("--outliers", args->outliers, "none | scattered | appearing")
      ->capture_default_str();
  cmd->add_option("--share", args->share, "share of the current scan made outliers")
      ->capture_default_str();
  cmd->add_flag("--least-squares", args->least_squares, "plain least squares instead of Huber");
  cmd->add_option("--success-xy", args->success_xy,
                  "success radius (m; default 1 mm without noise, 3 cm with)");
  cmd->add_option("--success-deg", args->success_deg,
                  "success heading error (deg; default 0.01 without noise, 0.3 with)");
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
