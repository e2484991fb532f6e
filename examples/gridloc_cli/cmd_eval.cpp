// gridloc eval: seed 001's protocol over {turned, oriented} x {raw, thinned}, or over the
// estimators (--estimators), with the sonar ring or a simulated laser (--laser); on polygon
// maps, or with a sector estimator, the sector protocol (eval_sectors.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "eval_sectors.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "options.hpp"

namespace gridloc::cli {
namespace {

/// The bundled polygon maps: the sector protocol's default.
constexpr const char* kPolygonMaps =
    "polygons/room_rect,polygons/room_l,polygons/room_furnished,polygons/office";

struct EvalArgs {
  std::string maps, ring, noise = "realistic";
  bool maps_given = false;  ///< --maps was on the command line
  double step_xy = 0.1;     ///< the correlation's grid cell = translation step (m)
  SearchArgs search;
  OctomapArgs octomap;
  int trials = 100;
  std::uint64_t seed = 1;
  bool json = false;
  bool quiet = false;
  bool noisy = false;
  bool echo_filter = false;
  std::string trials_out;
  std::string estimators;  ///< empty: the correlation over the four model configurations
  LaserProtocol laser;
};

/// One line per trial and configuration: what calibration studies need.
void write_trials(const std::string& path, const EvalReport& report, const EvalOptions& options) {
  std::ofstream out(path);
  if (!out) throw Error("--trials-out: cannot write " + path);
  out << "map,trial,local,global,success,wrong_prior,furniture,position_error_m,"
         "heading_error_deg,score,normalized_score,second_score,confidence,std_x,std_y,"
         "std_theta,on_window_edge,agreement,rejected_sonars,estimator\n";
  for (const TrialRecord& r : report.records) {
    const EvalConfiguration& c = options.configurations[r.configuration];
    const Estimate& e = r.estimate;
    out << r.map << ',' << r.trial << ',' << to_string(c.local) << ',' << to_string(c.global) << ','
        << r.success << ',' << r.wrong_prior << ',' << r.furniture << ',' << r.position_error_m
        << ',' << r.heading_error_deg << ',' << e.score << ',' << e.normalized_score << ','
        << e.second_score << ',' << e.confidence << ',' << std::sqrt(e.covariance(0, 0)) << ','
        << std::sqrt(e.covariance(1, 1)) << ',' << std::sqrt(e.covariance(2, 2)) << ','
        << e.on_window_edge << ',' << e.agreement << ',' << r.rejected_sonars << ','
        << to_string(c.estimator) << '\n';
  }
  if (!out) throw Error("--trials-out: writing " + path + " failed");
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

/// A bare name ("room_l", "polygons/office") means a bundled map.
std::string map_file(const std::string& name) {
  return name.find(".yaml") == std::string::npos && !is_octomap_path(name)
             ? data_dir() + "/" + name + ".yaml"
             : name;
}

/// The sector protocol: polygon maps, 360-degree scans, no prior.
void run_sectors(const EvalArgs& args, const std::vector<std::string>& files) {
  if (args.noisy || args.echo_filter) {
    throw Error(
        "--noisy and --echo-filter belong to seed 001's sonar protocol, not to the sector "
        "protocol (polygon maps, 360 degree scans)");
  }
  SectorEvalArgs sector_args;
  sector_args.maps = files;
  sector_args.json = args.json;
  sector_args.quiet = args.quiet;
  sector_args.trials_out = args.trials_out;
  SectorEvalOptions& options = sector_args.options;
  options.trials = args.trials;
  options.seed = args.seed;
  options.beams = args.laser.beams;
  options.max_range = args.laser.max_range;
  options.sigma_m = args.laser.sigma_m;
  args.search.apply(options.correlation);
  options.correlation.resolution = args.step_xy;
  if (!args.estimators.empty()) {
    options.estimators.clear();
    for (const auto& name : split(args.estimators)) {
      options.estimators.push_back(parse_estimator_kind(name));
    }
  }
  run_sector_eval(sector_args);
}

/// Throws unless --step-xy is a positive cell size.
void check_step(double step_xy) {
  if (!(step_xy > 0.0) || !std::isfinite(step_xy)) {
    throw Error("--step-xy must be a positive cell size in metres, got " + std::to_string(step_xy));
  }
}

/// True when --estimators names a sector estimator (they need the sector protocol).
bool names_a_sector_estimator(const std::string& estimators) {
  bool sectors = false;
  for (const auto& name : split(estimators)) {
    sectors |= is_sector_estimator(parse_estimator_kind(name));
  }
  return sectors;
}

/// The files of --maps (with sector estimators and no --maps, the bundled polygon maps);
/// throws when there is none or one does not exist.
std::vector<std::string> map_files(const EvalArgs& args, bool sector_estimators) {
  std::vector<std::string> files;
  for (const auto& name : split(sector_estimators && !args.maps_given ? kPolygonMaps : args.maps)) {
    files.push_back(map_file(name));
  }
  if (files.empty()) throw Error("--maps names no map");
  for (const auto& f : files) {
    if (!std::filesystem::exists(f)) throw Error("--maps: " + f + ": no such file");
  }
  return files;
}

/// True when `files` are polygon maps (the sector protocol), false when they are grid maps;
/// throws when they mix the two, or when sector estimators get grid maps.
bool polygon_maps(const std::vector<std::string>& files, bool sector_estimators) {
  const auto polygon = [](const std::string& f) {
    return !is_octomap_path(f) && is_polygon_map_file(f);
  };
  const std::size_t polygons =
      static_cast<std::size_t>(std::count_if(files.begin(), files.end(), polygon));
  if (polygons > 0 && polygons < files.size()) {
    throw Error(
        "--maps mixes polygon maps with grid maps: the sector protocol needs polygon maps only");
  }
  if (sector_estimators && polygons == 0) {
    throw Error(
        "the sectors estimators need polygon maps (--maps polygons/office or a polygon YAML; "
        "README, Polygon maps)");
  }
  return polygons > 0;
}

/// Seed 001's protocol options from the command line.
EvalOptions eval_options(const EvalArgs& args) {
  EvalOptions options;
  options.trials = args.trials;
  options.seed = args.seed;
  args.search.apply(options.search);
  options.search.resolution = options.window.step_xy = args.step_xy;
  if (args.noise == "none") {
    options.noise = SonarSimOptions{};
  } else if (args.noise != "realistic") {
    throw Error("--noise must be realistic or none, not '" + args.noise + "'");
  }
  options.noisy.enabled = args.noisy;
  options.laser = args.laser;
  if (!args.estimators.empty()) {
    // One configuration per estimator, the correlation with seed 001's best models.
    options.configurations.clear();
    for (const auto& name : split(args.estimators)) {
      options.configurations.push_back(
          {LocalModel::Oriented, GlobalModel::Thinned, parse_estimator_kind(name)});
    }
    if (options.configurations.empty()) throw Error("--estimators names no estimator");
  }
  if (args.echo_filter) options.echo_filter = EchoFilterOptions{};
  return options;
}

/// Sonars the echo filter rejected, per trial (each trial's readings serve every configuration).
double mean_rejected_sonars(const EvalReport& report) {
  double rejected = 0.0;
  for (const TrialRecord& r : report.records) {
    if (r.configuration == 0) rejected += r.rejected_sonars;
  }
  rejected /= report.trials;
  return rejected;
}

/// The report as JSON on stdout.
void print_json(const EvalArgs& args, const std::vector<EvalMap>& maps, const EvalReport& report,
                double rejected_per_trial) {
  nlohmann::json configs = nlohmann::json::array();
  for (const auto& c : report.configurations) {
    configs.push_back(
        {{"estimator", to_string(c.configuration.estimator)},
         {"local", to_string(c.configuration.local)},
         {"global", to_string(c.configuration.global)},
         {"success_rate", c.success_rate},
         {"successes", c.successes},
         {"mean_position_error_m", c.mean_position_error_m},
         {"mean_heading_error_deg", c.mean_heading_error_deg},
         {"median_ms", c.median_ms},
         {"sector_identification_rate", nullptr},  // the sector protocol's
         {"auroc", number_or_null(c.auroc)},
         {"failures_flagged_at_95_recall", number_or_null(c.failures_flagged_at_95_recall)}});
  }
  nlohmann::json names = nlohmann::json::array();
  for (const auto& m : maps) names.push_back(m.name);
  std::cout << nlohmann::json{{"trials", report.trials},
                              {"maps", names},
                              {"seed", args.seed},
                              {"strategy", args.search.strategy},
                              // The sonar noise; the laser's is laser_noise_m.
                              {"noise", args.noisy ? "noisy" : args.noise},
                              {"laser_noise_m", args.laser.enabled
                                                    ? nlohmann::json(args.laser.sigma_m)
                                                    : nlohmann::json(nullptr)},
                              {"noisy", args.noisy},
                              {"sensor", args.laser.enabled ? "laser" : "sonar"},
                              {"echo_filter", args.echo_filter},
                              {"echo_filter_rejected_per_trial", rejected_per_trial},
                              {"arc_rule", args.search.arc_rule},
                              {"arc_depth_cells", args.search.arc_depth},
                              {"configurations", configs}}
                   .dump(2)
            << "\n";
}

/// The table's title lines: protocol, trials, search, noise, echo filter (and the laser).
void print_table_title(const EvalArgs& args, const EvalOptions& options, const SonarRing& ring,
                       std::size_t maps, const EvalReport& report, double rejected_per_trial) {
  char filter[96] = "echo filter off";
  if (args.echo_filter) {
    std::snprintf(filter, sizeof filter, "echo filter on (%d firings, %.2f of %zu sonars rejected)",
                  options.echo_firings, rejected_per_trial, ring.sonars.size());
  }
  std::printf(
      "seed 001 protocol%s: %d trials (%zu maps), seed %llu, %s search, %s noise, %s arcs of "
      "depth %.2g cells, %s\n",
      args.noisy ? " (noisy: harsh noise, wrong priors, furniture)" : "", report.trials, maps,
      static_cast<unsigned long long>(args.seed), args.search.strategy.c_str(),
      args.noisy ? "harsh" : args.noise.c_str(), args.search.arc_rule.c_str(),
      args.search.arc_depth, filter);
  if (args.laser.enabled) {
    std::printf("laser: %d beams, %.1f m max range, %.3f m noise\n", args.laser.beams,
                args.laser.max_range, args.laser.sigma_m);
  }
}

/// `v` times `scale` as a table cell: "-" for NaN, a percentage when `scale` > 1.
std::string percent_or_dash(double v, double scale) {
  char buf[32];
  if (std::isnan(v)) return std::string("-");
  std::snprintf(buf, sizeof buf, "%.*f", scale > 1.0 ? 1 : 3, v * scale);
  return std::string(buf) + (scale > 1.0 ? "%" : "");
}

/// One table row per configuration, under the column header, and the footnote.
void print_table_rows(const EvalReport& report) {
  std::printf("%-15s %-9s %-8s %9s %14s %16s %10s %7s %9s\n", "estimator", "local", "global",
              "success", "mean pos err", "mean head err", "median", "AUROC", "flagged");
  for (const auto& c : report.configurations) {
    const bool models = c.configuration.estimator != EstimatorKind::Icp;
    std::printf("%-15s %-9s %-8s %8.1f%% %12.3f m %12.2f deg %7.2f ms %7s %9s\n",
                to_string(c.configuration.estimator).c_str(),
                models ? to_string(c.configuration.local).c_str() : "-",
                models ? to_string(c.configuration.global).c_str() : "-", 100.0 * c.success_rate,
                c.mean_position_error_m, c.mean_heading_error_deg, c.median_ms,
                percent_or_dash(c.auroc, 1.0).c_str(),
                percent_or_dash(c.failures_flagged_at_95_recall, 100.0).c_str());
  }
  std::printf(
      "AUROC: how well the confidence separates successes from failures; flagged: failures "
      "below the confidence that keeps 95%% of successes.\n");
}

void run(const EvalArgs& args) {
  check_step(args.step_xy);
  // Polygon maps or a sector estimator: the sector protocol.
  const bool sector_estimators = names_a_sector_estimator(args.estimators);
  const std::vector<std::string> files = map_files(args, sector_estimators);
  if (polygon_maps(files, sector_estimators)) return run_sectors(args, files);

  const EvalOptions options = eval_options(args);
  std::vector<EvalMap> maps;
  for (const auto& file : files) maps.push_back({file, load_map(file, args.octomap.slice)});
  const SonarRing ring = load_sonar_ring(args.ring);
  const EvalReport report = run_evaluation(maps, ring, options, [&](int done, int total) {
    if (args.quiet) return;
    std::fprintf(stderr, "\r[eval] %d/%d poses (%zu maps x %d trials, %zu configurations)", done,
                 total, maps.size(), args.trials, options.configurations.size());
    if (done == total) std::fprintf(stderr, "\n");
  });

  if (!args.trials_out.empty()) write_trials(args.trials_out, report, options);
  const double rejected = mean_rejected_sonars(report);
  if (args.json) return print_json(args, maps, report, rejected);
  print_table_title(args, options, ring, maps.size(), report, rejected);
  print_table_rows(report);
}

}  // namespace

void add_eval(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  args->maps = "room_rect,room_l,room_furnished";
  args->ring = data_dir() + "/sensors/wheelchair_14.yaml";
  auto* cmd = app.add_subcommand("eval", "Run seed 001's evaluation protocol and print the table");
  cmd->add_option("--maps", args->maps,
                  "comma-separated bundled map names, YAML paths or OctoMap .bt/.ot paths; "
                  "polygon maps run the sector protocol (default there: " +
                      std::string(kPolygonMaps) + ")")
      ->capture_default_str()
      ->each([args](const std::string&) { args->maps_given = true; });
  args->octomap.add_to(cmd);
  cmd->add_option("--ring", args->ring, "sonar ring YAML")->capture_default_str();
  cmd->add_option("--trials", args->trials, "random poses per map")->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of poses, priors and noise")->capture_default_str();
  cmd->add_option("--noise", args->noise, "realistic | none")->capture_default_str();
  args->search.add_to(cmd);
  cmd->add_option("--step-xy", args->step_xy,
                  "the correlation search's grid cell and translation step (m; seed 001: 0.1)")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print JSON instead of the table");
  cmd->add_flag("--quiet", args->quiet, "no progress line");
  cmd->add_flag("--noisy", args->noisy,
                "the calibration protocol: harsh noise (3 cm + 2 %, 5 % dropouts and "
                "crosstalk, specular beyond 60 deg), 15 % wrong priors, 25 % furniture changes");
  cmd->add_flag("--echo-filter", args->echo_filter,
                "fire the ring 3 times per trial and reject sonars whose echoes disagree "
                "(EERUF-like; a rejected sonar adds nothing to the local grid)");
  cmd->add_option("--estimators,--estimator", args->estimators,
                  "compare these estimators on the same trials: comma-separated correlation, "
                  "icp, correlation+icp (icp needs --laser), sectors, sectors+correlation (the "
                  "sector protocol: polygon maps, 360 degree scans, no prior); default: the "
                  "correlation over {turned, oriented} x {raw, thinned}, or sectors and "
                  "correlation on polygon maps");
  cmd->add_flag("--laser", args->laser.enabled,
                "observe with a simulated 360 degree laser instead of the sonar ring");
  cmd->add_option("--laser-beams", args->laser.beams, "laser beams per scan")
      ->capture_default_str();
  cmd->add_option("--laser-max-range", args->laser.max_range, "laser max range (m)")
      ->capture_default_str();
  cmd->add_option("--laser-noise", args->laser.sigma_m, "laser range noise sigma (m)")
      ->capture_default_str();
  cmd->add_option("--trials-out", args->trials_out,
                  "write every trial (errors, scores, confidence, std) to this CSV");
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
