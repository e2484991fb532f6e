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

void run(const HallwayArgs& a) {
  HallwayTrialsOptions o;
  o.seeds = a.seeds;
  o.noise_m = a.noise_m;
  o.outliers = parse_outlier_kind(a.outliers);
  o.share = a.share;
  o.icp.robust = !a.least_squares;
  o.success_xy = a.success_xy > 0.0 ? a.success_xy : (a.noise_m > 0.0 ? 0.03 : 0.001);
  o.success_deg = a.success_deg > 0.0 ? a.success_deg : (a.noise_m > 0.0 ? 0.3 : 0.01);
  const HallwayReport r = run_hallway_trials(o);
  const nlohmann::json j = {{"seeds", r.seeds},
                            {"noise_m", o.noise_m},
                            {"outliers", to_string(o.outliers)},
                            {"share", o.outliers == OutlierKind::None ? 0.0 : o.share},
                            {"estimator", a.least_squares ? "least squares" : "huber"},
                            {"success_xy_m", o.success_xy},
                            {"success_deg", o.success_deg},
                            {"successes", r.successes},
                            {"converged", r.converged},
                            {"mean_error_x_mm", 1000.0 * r.mean_error_x_m},
                            {"mean_error_y_mm", 1000.0 * r.mean_error_y_m},
                            {"mean_error_deg", r.mean_error_deg},
                            {"mean_iterations", r.mean_iterations}};
  if (a.json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf(
      "seed 004 hallway, %d seeds, %.3f m noise, outliers %s: %d within %.3f m and %.2f deg "
      "(%d converged); over those, mean errors %.2f mm, %.2f mm, %.3f deg, %.1f iterations\n",
      r.seeds, o.noise_m, to_string(o.outliers).c_str(), r.successes, o.success_xy, o.success_deg,
      r.converged, 1000.0 * r.mean_error_x_m, 1000.0 * r.mean_error_y_m, r.mean_error_deg,
      r.mean_iterations);
}

}  // namespace

void add_hallway(CLI::App& app) {
  auto a = std::make_shared<HallwayArgs>();
  auto* cmd = app.add_subcommand(
      "hallway", "Seed 004's robust ICP simulation over seeds: errors and iterations");
  cmd->add_option("--seeds", a->seeds, "runs (seeds 1..N)")->capture_default_str();
  cmd->add_option("--noise", a->noise_m, "Gaussian range noise on both scans (m)")
      ->capture_default_str();
  cmd->add_option("--outliers", a->outliers, "none | scattered | appearing")->capture_default_str();
  cmd->add_option("--share", a->share, "share of the current scan made outliers")
      ->capture_default_str();
  cmd->add_flag("--least-squares", a->least_squares, "plain least squares instead of Huber");
  cmd->add_option("--success-xy", a->success_xy,
                  "success radius (m; default 1 mm without noise, 3 cm with)");
  cmd->add_option("--success-deg", a->success_deg,
                  "success heading error (deg; default 0.01 without noise, 0.3 with)");
  cmd->add_flag("--json", a->json, "print JSON");
  cmd->callback([a] { run(*a); });
}

}  // namespace gridloc::cli
