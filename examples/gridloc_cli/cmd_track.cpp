// gridloc track: the Localizer run through a CARMEN log, one JSON object per processed scan
// (JSON Lines) or a progress line and a summary (issue 13).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gridloc/engine/evaluation/log_tracking.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/gfs_odometry.hpp"
#include "gridloc/sensors/log_split.hpp"
#include "limit_options.hpp"
#include "localization_args.hpp"
#include "options.hpp"
#include "plot.hpp"
#include "progress.hpp"
#include "stdin_input.hpp"
#include "track_render.hpp"
#include "track_trials.hpp"

namespace gridloc::cli {
namespace {

struct TrackArgs {
  std::string map, log, prior, odometry = "laser", odometry_noise, raw_odometry;
  std::string odometry_error = "0.05,5";
  /// --global-grid and --field-*: by default the laser tracking grid
  /// (with_laser_tracking_grid).
  std::string global_grid = "field";
  FieldArgs field{with_laser_tracking_grid({}).field};
  std::string plot;  ///< --plot FILE.png
  double entry_weight = HypothesisWeightOptions{}.entry_weight;
  double evidence_per_scan = HypothesisWeightOptions{}.evidence_per_scan;
  double localized_fit_ratio = LocalizerOptions{}.localized_fit_ratio;
  double weak_fit_ratio = LocalizerOptions{}.weak_fit_ratio;
  double max_window_turn_deg = LocalizerOptions{}.max_half_theta * 180.0 / std::numbers::pi;
  double poses_per_slice = SlicedSearchOptions{}.poses_per_slice;
  double cells_per_update = SlicedSearchOptions{}.cells_per_update;
  int catch_up_steps = SlicedSearchOptions{}.catch_up_steps;
  double search_resolution = SlicedSearchOptions{}.resolution;
  double light_place_weight = LocalizerOptions{}.light_place_weight;
  double reported_floor_m = LocalizerOptions{}.reported_floor_m;
  double reported_floor_deg = rad2deg(LocalizerOptions{}.reported_floor_rad);
  bool global = false, json = false, truth = false, prior_from_log = false, fuse_drive = false;
  bool keep_re_searches = false, unfused_positions = false;
  int every = 1;
  std::size_t start = 0, count = 0;
  double max_range = 20.0, resolution = 0.0, prior_sigma_m = 0.1, prior_sigma_deg = 5.0;
  std::uint64_t seed = 1;
  double window_m = DriveWindowOptions{}.max_distance_m;
  double drop_ratio = HypothesisSetOptions{}.drop_ratio;
  std::string part = "all";
  LogSplitOptions split;
  GlobalTrialOptions trials;  ///< --trials N (0: track the log once)
  int trial_count = 0;
  std::string shard;  ///< --shard K/N
};

/// What the summary counts over the processed scans.
struct TrackTally {
  int steps = 0, localized = 0, ambiguous = 0, not_localized = 0, wrong_localized = 0;
  int rejected_jumps = 0, searches = 0, jumps = 0;
  double error_sum_m = 0.0, error_sum_deg = 0.0, time_ms = 0.0, worst_jump_m = 0.0;
  std::vector<double> times_ms;
  std::vector<double> losses_m;  ///< path driven in each run of answers not `localized`
  std::optional<TrackStep> last_localized;
  std::optional<double> loss_from_m;     ///< where the current loss began (path driven)
  std::map<std::string, int> held_back;  ///< scans not localized, by the rule that held them

  void add(const TrackStep& step, bool truth) {
    ++steps;
    time_ms += step.timing_ms;
    times_ms.push_back(step.timing_ms);
    rejected_jumps += step.status.jump_rejected;
    searches += step.status.search_finished;
    const Verdict verdict = step.estimate.verdict;
    localized += verdict == Verdict::Localized;
    ambiguous += verdict == Verdict::Ambiguous;
    not_localized += verdict == Verdict::NotLocalized;
    if (verdict == Verdict::NotLocalized) ++held_back[to_string(step.status.held_back)];
    if (verdict != Verdict::Localized) {
      if (!loss_from_m) loss_from_m = step.travelled_m;
      return;
    }
    if (loss_from_m) losses_m.push_back(step.travelled_m - *loss_from_m);
    loss_from_m.reset();
    count_jump(step);
    last_localized = step;
    if (!truth) return;
    error_sum_m += step.error_m;
    error_sum_deg += step.error_deg;
    wrong_localized += step.error_m > 0.1 || step.error_deg > 2.0;  // issue 13's laser success
  }
  /// A jump (issue 34): consecutive `localized` answers more than 1 m apart beyond what the
  /// odometry moved between them, within 2 m of driving (farther, the odometry's own error
  /// may reach a metre).
  void count_jump(const TrackStep& step) {
    if (!last_localized || step.travelled_m - last_localized->travelled_m > 2.0) return;
    const Pose2 moved = relative_pose(last_localized->odometry, step.odometry);
    const Pose2 expected = compose(last_localized->estimate.pose, moved);
    const double off =
        std::hypot(step.estimate.pose.x - expected.x, step.estimate.pose.y - expected.y);
    jumps += off > 1.0;
    if (off > 1.0) worst_jump_m = std::max(worst_jump_m, off);
  }
};

/// One JSON line of a scan; `truth` is the log's pose with --truth-from-log.
nlohmann::json step_json(const TrackStep& step, const std::optional<Pose2>& truth) {
  const Estimate& e = step.estimate;
  const nlohmann::json estimate = cli::to_json(e);
  nlohmann::json search = nullptr;
  if (step.status.search_slices > 0) {
    search = {{"slices_done", step.status.search_slices_done},
              {"slices", step.status.search_slices},
              {"progress", step.status.search_progress},
              {"finished", step.status.search_finished}};
  }
  nlohmann::json line = {{"index", step.index},
                         {"search", search},
                         {"jump_rejected", step.status.jump_rejected},
                         {"confirming", step.status.confirming},
                         {"held_back", to_string(step.status.held_back)},
                         {"time", step.time},
                         {"pose", cli::to_json(e.pose)},
                         {"verdict", to_string(e.verdict)},
                         {"confidence", e.confidence},
                         {"hypotheses", e.alternatives.size()},
                         {"alternatives", estimate["alternatives"]},
                         {"covariance", estimate["covariance"]},
                         {"travelled_m", step.travelled_m},
                         {"odometry", cli::to_json(step.odometry)},
                         {"timing_ms", step.timing_ms}};
  if (truth) {
    line["truth"] = cli::to_json(*truth);
    line["error_m"] = step.error_m;
    line["error_deg"] = step.error_deg;
  }
  return line;
}

/// The scans of --part: every scan, or the held-out part of alternate blocks (the scans
/// `map-from-log --part map` with the same split options did not draw).
std::vector<std::size_t> part_scans(const TrackArgs& args, const CarmenLog& log) {
  if (args.part == "held-out") return split_log(log.lasers, args.split).held_out;
  if (args.part != "all") throw Error("--part must be all or held-out, not '" + args.part + "'");
  return all_scans(log.lasers).map;
}

/// The options the arguments give, checked against the log.
LogTrackingOptions tracking_options(const TrackArgs& args, const CarmenLog& log,
                                    const OccupancyMap& map) {
  if (int(args.global) + int(!args.prior.empty()) + int(args.prior_from_log) != 1) {
    throw Error("give one of --prior x,y,theta, --prior-from-log or --global");
  }
  require_flag(args.trial_count >= 0, "--trials", args.trial_count, "must be >= 0");
  const double min_turn_deg = rad2deg(LocalizerOptions{}.min_half_theta);
  require_flag(args.max_window_turn_deg >= min_turn_deg && std::isfinite(args.max_window_turn_deg),
               "--max-window-turn", args.max_window_turn_deg,
               "must be a finite number of degrees >= " + message_number(min_turn_deg));
  if (args.trial_count > 0 && !args.global) throw Error("--trials needs --global");
  require_flag(args.reported_floor_m >= 0.0 && args.reported_floor_m <= 100.0, "--reported-floor-m",
               args.reported_floor_m, "must lie in [0, 100] m");
  require_flag(args.reported_floor_deg >= 0.0 && args.reported_floor_deg <= 180.0,
               "--reported-floor-deg", args.reported_floor_deg, "must lie in [0, 180] degrees");
  require_flag(args.resolution >= 0.0 && std::isfinite(args.resolution), "--resolution",
               args.resolution, "must be a finite cell size >= 0 (0: the map's cell)");
  require_flag(args.weak_fit_ratio >= 0.0 && args.weak_fit_ratio <= 1.0, "--weak-fit-ratio",
               args.weak_fit_ratio, "must lie in [0, 1]");
  require_flag(args.cells_per_update >= 0.0 && std::isfinite(args.cells_per_update),
               "--cells-per-update", args.cells_per_update,
               "must be a finite number >= 0 (0: heading slices)");
  require_flag(args.catch_up_steps >= 0 && args.catch_up_steps <= 1000, "--catch-up-steps",
               args.catch_up_steps, "must lie in [0, 1000]");
  LogTrackingOptions options;
  options.localizer.correlation.limits = limits();
  options.localizer.correlation.resolution =
      args.resolution > 0.0 ? args.resolution : map.geometry.resolution;
  options.localizer.drive.max_distance_m = args.window_m;
  options.localizer.hypothesis_set.drop_ratio = args.drop_ratio;
  options.localizer.weights.entry_weight = args.entry_weight;
  options.localizer.weights.evidence_per_scan = args.evidence_per_scan;
  options.localizer.localized_fit_ratio = args.localized_fit_ratio;
  options.localizer.weak_fit_ratio = args.weak_fit_ratio;
  options.localizer.correlation.global = parse_global(args.global_grid);
  args.field.apply(options.localizer.correlation);
  options.localizer.max_half_theta = args.max_window_turn_deg * std::numbers::pi / 180.0;
  options.localizer.research.poses_per_slice = args.poses_per_slice;
  options.localizer.research.cells_per_update = args.cells_per_update;
  options.localizer.research.catch_up_steps = args.catch_up_steps;
  options.localizer.research.resolution = args.search_resolution;
  options.localizer.research.drop_once_localized = !args.keep_re_searches;
  options.localizer.fuse_carried_position = !args.unfused_positions;
  options.localizer.light_place_weight = args.light_place_weight;
  options.localizer.reported_floor_m = args.reported_floor_m;
  options.localizer.reported_floor_rad = deg2rad(args.reported_floor_deg);
  const OdometryNoise model = parse_odometry_noise(args.odometry_error, "--odometry-error");
  options.localizer.odometry_error_per_m = options.localizer.jump_gate.odometry_error_per_m =
      model.frac;
  options.localizer.odometry_turn_error_per_m =
      options.localizer.jump_gate.odometry_turn_error_per_m = model.rad_per_m;
  if (!args.raw_odometry.empty()) {
    options.raw_odometry = scan_odometry_from_gfs(
        log, load_gfs_scans(input_path(args.raw_odometry, "--raw-odometry"), limits()));
  }
  options.laser.max_range = args.max_range;
  options.laser.fuse_drive = args.fuse_drive;
  options.laser.tracking_field = false;  // --global-grid and --field-* say which grid
  options.odometry = parse_odometry_source(args.odometry);
  if (!args.odometry_noise.empty())
    options.odometry_noise = parse_odometry_noise(args.odometry_noise);
  options.seed = args.seed;
  if (!args.prior.empty()) options.prior = parse_pose(args.prior, "--prior");
  const double sxy = args.prior_sigma_m, sth = deg2rad(args.prior_sigma_deg);
  options.prior_covariance = Eigen::Vector3d(sxy * sxy, sxy * sxy, sth * sth).asDiagonal();
  options.every = args.every;
  if (args.start >= log.lasers.size()) {
    throw Error("--start " + std::to_string(args.start) + " is past the log's " +
                std::to_string(log.lasers.size()) + " scans");
  }
  const std::size_t end =
      args.count == 0 ? log.lasers.size() : std::min(log.lasers.size(), args.start + args.count);
  for (std::size_t k : part_scans(args, log)) {
    if (k >= args.start && k < end) options.scans.push_back(k);
  }
  if (options.scans.empty())
    throw Error("no scan of the " + args.part + " part in --start/--count");
  if (args.prior_from_log) options.prior = log.lasers[options.scans.front()].robot_pose;
  return options;
}

/// The q-quantile of `values` (nearest rank); 0 for none.
template <class T>
double quantile(std::vector<T> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return static_cast<double>(values[std::clamp<std::size_t>(rank, 1, values.size()) - 1]);
}

void print_summary(const TrackTally& tally, bool truth) {
  std::fprintf(stderr, "\n");
  std::printf(
      "%d scans: %d localized, %d ambiguous, %d not localized; %.1f ms per update (%.1f/s)\n",
      tally.steps, tally.localized, tally.ambiguous, tally.not_localized,
      tally.time_ms / std::max(1, tally.steps),
      tally.time_ms > 0.0 ? 1000.0 * tally.steps / tally.time_ms : 0.0);
  std::printf(
      "update: median %.1f ms, p99 %.1f ms, max %.1f ms; %d searches finished; %d jumps "
      "over 1 m within 2 m of driving (worst %.1f m), %d rejected; %zu losses, the longest over "
      "%.1f m\n",
      quantile(tally.times_ms, 0.5), quantile(tally.times_ms, 0.99), quantile(tally.times_ms, 1.0),
      tally.searches, tally.jumps, tally.worst_jump_m, tally.rejected_jumps,
      tally.losses_m.size() + (tally.loss_from_m ? 1 : 0), quantile(tally.losses_m, 1.0));
  if (!tally.held_back.empty()) {
    std::vector<std::pair<std::string, int>> reasons(tally.held_back.begin(),
                                                     tally.held_back.end());
    std::stable_sort(reasons.begin(), reasons.end(),
                     [](const auto& a, const auto& b) { return a.second > b.second; });
    std::printf("not localized, held back by:");
    for (const auto& [reason, count] : reasons) std::printf(" %s %d", reason.c_str(), count);
    std::printf("\n");
  }
  if (truth && tally.localized > 0) {
    std::printf("localized: mean error %.3f m, %.2f deg; %d beyond 10 cm or 2 deg\n",
                tally.error_sum_m / tally.localized, tally.error_sum_deg / tally.localized,
                tally.wrong_localized);
  }
}

/// --trials: global localization from a standstill and from a drive, from seeded starts
/// (with --shard, this shard's trials and a summary of them naming the shard).
void run_trials(const TrackArgs& args, const CarmenLog& log, const OccupancyMap& map,
                const LogTrackingOptions& options) {
  Localizer localizer(map, options.laser, options.localizer);
  GlobalTrialOptions trials = args.trials;
  trials.trials = args.trial_count;
  if (!args.shard.empty()) trials.shard = parse_shard(args.shard);
  std::vector<nlohmann::json> lines;
  const auto progress = progress_line("track", "trials", args.json);
  run_global_trials(log, localizer, options, options.scans, trials, [&](const GlobalTrial& trial) {
    lines.push_back(trial_json(trial, trials));
    if (args.json) {
      std::cout << lines.back().dump() << "\n" << std::flush;
    } else {
      progress(trial.trial + 1, trials.trials);
    }
  });
  nlohmann::json summary = {{"summary", trials_summary(lines)}};
  if (!args.shard.empty()) {
    summary["shard"] = {{"index", trials.shard.index + 1},
                        {"count", trials.shard.count},
                        {"trials", trials.trials}};
  }
  if (args.json) {
    std::cout << summary.dump() << "\n";
  } else {  // the summary alone, as before shards, or with its shard
    std::fprintf(stderr, "\n");
    std::cout << (args.shard.empty() ? summary["summary"] : summary).dump(2) << "\n";
  }
}

/// Refuses a --plot path whose folder is missing before the run, not after it.
void check_plot_path(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent)) {
    throw Error("--plot " + path + ": the folder " + parent.string() + " does not exist");
  }
}

/// --plot: the track over the map, the weights over the updates.
void write_plot(const TrackArgs& args, const CarmenLog& log, const OccupancyMap& map,
                std::vector<TrackStep> steps, const TrackTally& tally) {
  TrackPicture picture;
  picture.map = map;
  for (const TrackStep& step : steps) {
    if (args.truth) picture.truth.push_back(log.lasers[step.index].robot_pose);
  }
  picture.steps = std::move(steps);
  picture.title = "gridloc track: " + std::filesystem::path(args.log).filename().string();
  std::ostringstream caption;
  caption << tally.steps << " scans: " << tally.localized << " localized, " << tally.ambiguous
          << " ambiguous, " << tally.not_localized << " not localized; " << tally.searches
          << " searches finished, " << tally.rejected_jumps << " jumps rejected";
  picture.caption = caption.str();
  plot::write_png(args.plot, render_track(picture));
}

void run(const TrackArgs& args) {
  if (!args.shard.empty()) {  // refused before the map and the log are read
    if (args.trial_count < 1) throw Error("--shard splits --trials: give --trials N too");
    parse_shard(args.shard);
  }
  const OccupancyMap map = load_map(args.map);
  CarmenOptions carmen;
  carmen.limits = limits();
  const CarmenLog log = load_carmen_log(input_path(args.log, "--log"), carmen);
  const LogTrackingOptions options = tracking_options(args, log, map);
  if (args.trial_count > 0) return run_trials(args, log, map, options);
  if (!args.plot.empty()) check_plot_path(args.plot);
  TrackTally tally;
  std::vector<TrackStep> steps;
  const auto progress = progress_line("track", "scans of the log", args.json);
  track_log(log, map, options, [&](const TrackStep& step) {
    tally.add(step, args.truth);
    if (!args.plot.empty()) steps.push_back(step);
    if (args.json) {
      std::cout << step_json(step, args.truth
                                       ? std::optional<Pose2>(log.lasers[step.index].robot_pose)
                                       : std::nullopt)
                       .dump()
                << "\n"
                << std::flush;
      return;
    }
    progress(static_cast<int>(step.index + 1), static_cast<int>(log.lasers.size()));
  });
  if (!args.plot.empty()) write_plot(args, log, map, std::move(steps), tally);
  if (!args.json) print_summary(tally, args.truth);
}

/// The options of the odometry, the laser, the search and the trials.
void add_sensor_options(CLI::App* cmd, TrackArgs& args) {
  cmd->add_option("--odometry", args.odometry,
                  "laser (the laser lines' pose fields) | odom (the ODOM lines)")
      ->capture_default_str();
  cmd->add_option("--odometry-noise", args.odometry_noise,
                  "seeded systematic odometry error FRAC,DEG_PER_M[,SLIP_EVERY_M] (length share, "
                  "heading drift per metre, a 0.3 m / 10 deg slip every ~SLIP_EVERY_M m), for "
                  "logs whose poses are corrected");
  cmd->add_option("--seed", args.seed, "seed of --odometry-noise")->capture_default_str();
  cmd->add_option("--raw-odometry", args.raw_odometry,
                  "the robot's own odometry from a GMapping .gfs file of the same run (its "
                  "LASER_READING poses, paired scan by scan with the log; - reads standard input)");
  cmd->add_option("--odometry-error", args.odometry_error,
                  "the tracker's odometry error model FRAC,DEG_PER_M: how fast its places' "
                  "covariances grow, and what the jump gate allows")
      ->capture_default_str();
  cmd->add_option("--entry-weight", args.entry_weight,
                  "the prior share of a place a re-search proposes against the tracked ones")
      ->capture_default_str();
  cmd->add_option("--evidence-per-scan", args.evidence_per_scan,
                  "log-likelihood per unit of a window's normalized score")
      ->capture_default_str();
  cmd->add_option("--global-grid", args.global_grid,
                  "the map's grid the scans are matched on: field (likelihood field, see "
                  "--field-sigma) | thinned | raw")
      ->capture_default_str();
  args.field.add_to(cmd);
  cmd->add_option("--localized-fit-ratio", args.localized_fit_ratio,
                  "a window scoring below this share of its place's usual normalized score is "
                  "not localized (0: no such rule)")
      ->capture_default_str();
  cmd->add_option("--weak-fit-ratio", args.weak_fit_ratio,
                  "a window scoring under half its place's usual normalized score but at least "
                  "this share of it still places the place when it lies where the odometry put "
                  "it (0.5: no such rule)")
      ->capture_default_str();
  cmd->add_option("--max-window-turn", args.max_window_turn_deg,
                  "a tracked place's window spans at most this many degrees either way")
      ->capture_default_str();
  cmd->add_option("--light-place-weight", args.light_place_weight,
                  "a place holding less than this share of the weights is re-scored in its "
                  "window alone: no look-alikes split off it, no second, wider look (0: none)")
      ->capture_default_str();
  cmd->add_option("--reported-floor-m", args.reported_floor_m,
                  "added to the reported position standard deviations in quadrature: the "
                  "map's own error, which a scan cannot see (README, issue 19); tracks and "
                  "verdicts do not change")
      ->capture_default_str();
  cmd->add_option("--reported-floor-deg", args.reported_floor_deg,
                  "the same for the heading (degrees)")
      ->capture_default_str();
  cmd->add_option("--search-resolution", args.search_resolution,
                  "cell (m) of the coarse copy of the map the whole-map searches run on, their "
                  "places then refined at the map's cell (0: the map's cell, exact)")
      ->capture_default_str();
  cmd->add_option("--poses-per-slice", args.poses_per_slice,
                  "a re-search is cut into heading slices of about this many lattice poses "
                  "(0: the whole search at once)")
      ->capture_default_str();
  cmd->add_option("--cells-per-update", args.cells_per_update,
                  "a re-search of more than one slice runs as one search advanced by about this "
                  "many cells or points read per update (0: one heading slice per update)")
      ->capture_default_str();
  cmd->add_option("--catch-up-steps", args.catch_up_steps,
                  "a finished re-search's places are carried to the latest scan through up to "
                  "this many of the scans taken meanwhile (0: by the odometry alone)")
      ->capture_default_str();
  cmd->add_flag("--keep-re-searches", args.keep_re_searches,
                "run a re-search to its end even once the track is localized again on one place "
                "(by default it is dropped then)");
  cmd->add_flag("--unfused-positions", args.unfused_positions,
                "place the track at each window's winner (by default its position is fused with "
                "where the odometry carried the place)");
  cmd->add_option("--max-range", args.max_range, "laser returns beyond this are no return (m)")
      ->capture_default_str();
  cmd->add_option("--resolution", args.resolution,
                  "translation step and grid cell (m; 0: the map's cell)")
      ->capture_default_str();
  cmd->add_flag("--fuse-drive", args.fuse_drive,
                "fuse each scan with the drive window's earlier scans (--drive-window-m) into "
                "one observation; off: each scan alone, the places' weights add them up");
  cmd->add_option("--drive-window-m", args.window_m,
                  "--fuse-drive: scans up to this far back along the path join the latest")
      ->capture_default_str();
  cmd->add_option("--trials", args.trial_count,
                  "with --global: this many global localizations from seeded starts, each "
                  "driving on until --drive-m; prints each trial and a summary")
      ->capture_default_str();
  cmd->add_option("--drive-m", args.trials.drive_m, "--trials: the drive's length (m)")
      ->capture_default_str();
  cmd->add_option("--shard", args.shard,
                  "--trials: run only shard K of N (1-based K/N: the trials t with t % N == "
                  "K - 1, each exactly as in the whole run); `gridloc merge` joins the shards' "
                  "--json outputs");
  cmd->add_option("--drop-ratio", args.drop_ratio,
                  "hypotheses scoring less than this share of the best are dropped; while two "
                  "survive the answer is ambiguous")
      ->capture_default_str();
}

}  // namespace

void add_track(CLI::App& app) {
  auto args = std::make_shared<TrackArgs>();
  auto* cmd = app.add_subcommand(
      "track", "Run the Localizer through a CARMEN laser log (JSON Lines with --json)");
  cmd->add_option("--map", args->map,
                  "map: map_server YAML, OctoMap or polygon YAML (- reads standard input)")
      ->required();
  cmd->add_option("--log", args->log,
                  "CARMEN log (FLASER / ROBOTLASER1 lines; .gz read too; - reads standard input)")
      ->required();
  cmd->add_option("--prior", args->prior, "the pose at the first scan: x,y,theta (m, m, rad)");
  cmd->add_flag("--global", args->global, "localize the first scans on the whole map");
  cmd->add_flag("--prior-from-log", args->prior_from_log,
                "the prior is the log's pose at the first scan (corrected logs: tracking from "
                "a correct prior)");
  cmd->add_option("--prior-sigma-m", args->prior_sigma_m, "--prior: its standard deviation (m)")
      ->capture_default_str();
  cmd->add_option("--prior-sigma-deg", args->prior_sigma_deg, "--prior: in heading (degrees)")
      ->capture_default_str();
  cmd->add_option("--every", args->every, "process every N-th scan (odometry from all)")
      ->capture_default_str();
  cmd->add_option("--start", args->start, "the first scan (0-based index)")->capture_default_str();
  cmd->add_option("--count", args->count, "this many scans from --start (0: to the end)")
      ->capture_default_str();
  cmd->add_option("--part", args->part,
                  "all | held-out: only the odd blocks of the split (odometry between them "
                  "carried), the scans map-from-log --part map leaves out")
      ->capture_default_str();
  cmd->add_option("--block-s", args->split.block_s, "--part: block length (s) by time")
      ->capture_default_str();
  cmd->add_option("--block-scans", args->split.block_scans,
                  "--part: block length (scans) when the timestamps are unusable")
      ->capture_default_str();
  add_sensor_options(cmd, *args);
  cmd->add_flag("--truth-from-log", args->truth,
                "the log's poses are the truth (SLAM-corrected logs): add error_m, error_deg");
  cmd->add_flag("--json", args->json, "one JSON object per processed scan (JSON Lines)");
  cmd->add_option("--plot", args->plot,
                  "a PNG of the track over the map (by verdict, the truth with "
                  "--truth-from-log, searches, rejected jumps) and the places' weights");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--log"}, {"--raw-odometry"}});
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
