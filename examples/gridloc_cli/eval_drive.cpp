// gridloc eval --drive: the drive protocol's options, run, table and JSON.
#include "eval_drive.hpp"
#include "limit_options.hpp"
#include "options.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "gridloc/engine/evaluation/drive_protocol.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "progress.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

/// Refuses the other protocols' options, and drive options out of range, by their flags.
void check_args(const EvalArgs& args, const DriveArgs& drive) {
  require_flag(drive.drive_m > 0.0 && drive.drive_m <= 20.0, drive.distance_option, drive.drive_m,
               "must lie in (0, 20] m");
  require_flag(drive.firings >= 2, drive.firings_option, drive.firings, "must be at least 2");
  if (!(drive.window_m >= 0.0) || !std::isfinite(drive.window_m)) {
    throw Error(drive.window_option + " must be finite and >= 0");
  }
  if (args.noisy || args.echo_filter || args.laser.enabled || !args.estimators.empty() ||
      !args.trials_out.empty()) {
    throw Error(
        "--drive runs the drive protocol (the sonar ring, the correlation search): "
        "--noisy, --echo-filter, --laser, --estimators and --trials-out do not apply");
  }
}

DriveEvalOptions drive_options(const EvalArgs& args, const DriveArgs& drive) {
  DriveEvalOptions options;
  options.trials = args.trials;
  options.seed = args.seed;
  options.drive_m = drive.drive_m;
  options.firings = drive.firings;
  options.global = !drive.windowed;
  options.fusion.max_distance_m = drive.window_m;
  const OdometryNoise noise = parse_odometry_noise(drive.odometry_noise);
  options.odometry_noise_frac = noise.frac;
  options.odometry_noise_rad_per_m = noise.rad_per_m;
  args.search.apply(options.search);
  options.search.resolution = options.window.step_xy = args.step_xy;
  options.noise = parse_noise(args.noise);
  return options;
}

nlohmann::json tally_json(const DriveEvalTally& tally, int trials) {
  return {{"success_rate", static_cast<double>(tally.successes) / trials},
          {"successes", tally.successes},
          {"localized", tally.localized},
          {"ambiguous", tally.ambiguous},
          {"not_localized", tally.not_localized},
          {"confident_wrong", tally.confident_wrong},
          {"median_ms", tally.median_ms}};
}

void print_json(const DriveEvalOptions& options, const DriveEvalReport& report) {
  nlohmann::json maps = nlohmann::json::array();
  for (const DriveEvalRow& row : report.maps) {
    maps.push_back({{"map", row.map},
                    {"trials", row.trials},
                    {"standstill", tally_json(row.standstill, row.trials)},
                    {"drive", tally_json(row.drive, row.trials)}});
  }
  const nlohmann::json out = {{"protocol", "drive"},
                              {"drive_m", options.drive_m},
                              {"firings", options.firings},
                              {"odometry_noise",
                               {{"frac", options.odometry_noise_frac},
                                {"deg_per_m", rad2deg(options.odometry_noise_rad_per_m)}}},
                              {"drive_window_m", options.fusion.max_distance_m},
                              {"global", options.global},
                              {"seed", options.seed},
                              {"trials_per_map", options.trials},
                              {"maps", maps}};
  std::cout << out.dump(2) << "\n";
}

void print_tally(const char* label, const DriveEvalTally& tally, int trials) {
  std::printf("  %-12s %6.1f %%   %4d / %4d / %4d   %4d   %8.1f\n", label,
              100.0 * tally.successes / trials, tally.localized, tally.ambiguous,
              tally.not_localized, tally.confident_wrong, tally.median_ms);
}

void print_table(const DriveEvalOptions& options, const DriveEvalReport& report) {
  std::printf(
      "gridloc eval --drive: %.1f m straight drive, %d firings, odometry noise %.1f %% + %.1f "
      "deg/m, %s, seed %llu, %d trials per map\n",
      options.drive_m, options.firings, 100.0 * options.odometry_noise_frac,
      rad2deg(options.odometry_noise_rad_per_m),
      options.global ? "global (no prior)" : "seed 001's window", (unsigned long long)options.seed,
      options.trials);
  for (const DriveEvalRow& row : report.maps) {
    std::printf("%s\n  %-12s %8s   %-18s   %4s   %8s\n", row.map.c_str(), "", "success",
                "loc. / amb. / not", "conf. wrong", "median ms");
    print_tally("last firing", row.standstill, row.trials);
    print_tally("drive", row.drive, row.trials);
  }
}

}  // namespace

void add_drive_options(CLI::App* cmd, DriveArgs& drive) {
  CLI::Option* on = cmd->add_option("--drive", drive.drive_m,
                                    "the drive protocol: a straight drive of this many metres "
                                    "before the last firing, fused, against the last firing alone")
                        ->each([&drive](const std::string&) { drive.given = true; });
  cmd->add_option("--drive-firings", drive.firings, "--drive: firings along the drive")
      ->capture_default_str()
      ->needs(on);
  cmd->add_option("--odometry-noise", drive.odometry_noise,
                  "--drive: odometry error FRAC,DEG_PER_M (length share, heading drift per metre)")
      ->capture_default_str()
      ->needs(on);
  cmd->add_flag("--drive-windowed", drive.windowed,
                "--drive: search seed 001's window around a prior instead of the whole map")
      ->needs(on);
  cmd->add_option("--drive-window-m", drive.window_m,
                  "--drive: fuse the firings within this path length of the last (m)")
      ->capture_default_str()
      ->needs(on);
}

void add_drive_protocol_options(CLI::App* cmd, DriveArgs& drive) {
  drive.given = true;
  drive.drive_m = 2.0;
  drive.distance_option = "--distance";
  drive.firings_option = "--firings";
  drive.window_option = "--window-m";
  cmd->add_option("--distance", drive.drive_m,
                  "a straight drive of this many metres before the last firing, fused, against "
                  "the last firing alone")
      ->capture_default_str();
  cmd->add_option("--firings", drive.firings, "firings along the drive")->capture_default_str();
  cmd->add_option("--odometry-noise", drive.odometry_noise,
                  "odometry error FRAC,DEG_PER_M (length share, heading drift per metre)")
      ->capture_default_str();
  cmd->add_flag("--windowed", drive.windowed,
                "search seed 001's window around a prior instead of the whole map");
  cmd->add_option("--window-m", drive.window_m,
                  "fuse the firings within this path length of the last (m)")
      ->capture_default_str();
}

void run_drive_eval(const EvalArgs& args, const DriveArgs& drive,
                    const std::vector<std::string>& files) {
  check_args(args, drive);
  const DriveEvalOptions options = drive_options(args, drive);
  std::vector<EvalMap> maps;
  for (const auto& file : files)
    maps.push_back({file, load_map(file, args.octomap.slice, "--maps")});
  const SonarRing ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
  const DriveEvalReport report = run_drive_evaluation(
      maps, ring, options, progress_line("eval --drive", "trials", args.quiet));
  if (args.json) {
    print_json(options, report);
  } else {
    print_table(options, report);
  }
}

}  // namespace gridloc::cli
