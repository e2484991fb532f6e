// gridloc eval's protocols from their parsed options: which one the old spelling names, the
// checks each needs, then its run (eval_output.cpp, eval_drive.cpp, eval_sectors.cpp,
// eval_disambiguation.cpp and eval_team.cpp print the results).
#include "eval_protocols.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "eval_sectors.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

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
  return name != kStdin && name.find(".yaml") == std::string::npos && !is_octomap_path(name)
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
  require_flag(step_xy > 0.0 && std::isfinite(step_xy), "--step-xy", step_xy,
               "must be a positive cell size in metres");
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
    if (f != kStdin && !std::filesystem::exists(f)) throw Error("--maps: " + f + ": no such file");
  }
  return files;
}

/// True when `files` are polygon maps (the sector protocol), false when they are grid maps;
/// throws when they mix the two, or when sector estimators get grid maps.
bool polygon_maps(const std::vector<std::string>& files, bool sector_estimators) {
  const auto polygon = [](const std::string& f) { return is_polygon_map_input(f, "--maps"); };
  const std::size_t polygons =
      static_cast<std::size_t>(std::count_if(files.begin(), files.end(), polygon));
  if (polygons > 0 && polygons < files.size()) {
    throw Error(
        "--maps mixes polygon maps with grid maps: the sector protocol needs polygon maps only");
  }
  if (sector_estimators && polygons == 0) {
    throw Error(
        "the sectors estimators need polygon maps (--maps polygons/office or a polygon YAML; "
        "maps/README.md, Polygon map format)");
  }
  return polygons > 0;
}

/// Seed 001's protocol options from the command line.
EvalOptions eval_options(const EvalArgs& args) {
  EvalOptions options;
  options.trials = args.trials;
  options.seed = args.seed;
  args.search.apply(options.search);
  args.field.apply(options.search);
  options.search.resolution = options.window.step_xy = args.step_xy;
  options.noise = parse_noise(args.noise);
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
  if (!args.global_model.empty()) {  // the oriented model (or each estimator) on that grid
    const GlobalModel global = parse_global(args.global_model);
    if (args.estimators.empty()) options.configurations = {{LocalModel::Oriented, global}};
    for (auto& c : options.configurations) c.global = global;
  }
  if (args.echo_filter) options.echo_filter = EchoFilterOptions{};
  return options;
}

/// Seed 001's protocol on grid maps, with the sonar ring or the simulated laser.
void run_seed_001(const EvalArgs& args, const std::vector<std::string>& files) {
  const EvalOptions options = eval_options(args);
  std::vector<EvalMap> maps;
  for (const auto& file : files)
    maps.push_back({file, load_map(file, args.octomap.slice, "--maps")});
  const SonarRing ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
  const std::string what = "poses (" + std::to_string(maps.size()) + " maps x " +
                           std::to_string(args.trials) + " trials, " +
                           std::to_string(options.configurations.size()) + " configurations)";
  const EvalReport report =
      run_evaluation(maps, ring, options, progress_line("eval", what, args.quiet));

  if (!args.trials_out.empty()) write_trials(args.trials_out, report, options);
  if (!args.calibration_plot.empty()) {
    write_calibration(args.calibration_plot, report,
                      std::string("gridloc eval ") + (args.laser.enabled ? "laser" : "sonar") +
                          (args.noisy ? " --noisy" : "") + ": " + std::to_string(maps.size()) +
                          " maps x " + std::to_string(args.trials) + " trials, seed " +
                          std::to_string(args.seed));
  }
  const double rejected = mean_rejected_sonars(report);
  if (args.json) return print_json(args, maps, report, rejected);
  print_table_title(args, options, ring, maps.size(), report, rejected);
  print_table_rows(report);
}

/// Seed 002's protocol on random offices, or with --sensor the engine in the loop on --maps.
void run_disambiguation(const EvalArgs& args, const DriveArgs& drive,
                        const ProtocolArgs& protocol) {
  if (drive.given) throw Error("--drive and --protocol disambiguation are different protocols");
  const DisambiguationEvalArgs& options = protocol.disambiguation;
  if (options.sensor == "ir")
    throw Error(
        "--sensor ir goes with --protocol team; the disambiguation protocol takes sonar or laser");
  if (options.sensor.empty()) {
    return run_disambiguation_eval(options, args.seed, args.json, args.quiet);
  }
  EvalArgs maps = args;
  if (!args.maps_given) maps.maps = kDisambiguationMaps;
  EngineLoopInputs inputs;
  inputs.map_files = map_files(maps, false);
  if (polygon_maps(inputs.map_files, false)) {
    throw Error("--sensor runs the engine on occupancy maps, not polygon maps");
  }
  inputs.ring = args.ring;
  inputs.trials = args.trials;
  inputs.laser_max_range = args.laser.max_range;
  inputs.laser_sigma_m = args.laser.sigma_m;
  inputs.laser_beams = args.laser.beams;
  run_engine_loop_eval(options, inputs, args.seed, args.json, args.quiet);
}

/// Seed 003's team protocol on --maps (polygon or occupancy maps).
void run_team(const EvalArgs& args, const DriveArgs& drive, const ProtocolArgs& protocol) {
  if (drive.given) throw Error("--drive and --protocol team are different protocols");
  EvalArgs maps = args;
  if (!args.maps_given) maps.maps = kTeamMaps;
  TeamEvalInputs inputs;
  inputs.map_files = map_files(maps, false);
  inputs.sensor = protocol.disambiguation.sensor.empty() ? "ir" : protocol.disambiguation.sensor;
  inputs.ring = args.ring;
  inputs.trials = args.trials;
  inputs.laser_max_range = args.laser.max_range;
  inputs.laser_sigma_m = args.laser.sigma_m;
  inputs.laser_beams = args.laser.beams;
  run_team_eval(protocol.team, inputs, args.seed, args.json, args.quiet);
}

/// The drive protocol on grid maps with the sonar ring.
void run_drive(const EvalArgs& args, const DriveArgs& drive) {
  check_step(args.step_xy);
  const bool sector_estimators = names_a_sector_estimator(args.estimators);
  const std::vector<std::string> files = map_files(args, sector_estimators);
  if (sector_estimators || polygon_maps(files, false)) {
    throw Error(
        "--drive runs the drive protocol on grid maps with the sonar ring, not on "
        "polygon maps or with a sector estimator");
  }
  run_drive_eval(args, drive, files);
}

/// The sector protocol; throws unless --maps names polygon maps.
void run_sector_protocol(const EvalArgs& args) {
  check_step(args.step_xy);
  const bool sector_estimators = names_a_sector_estimator(args.estimators);
  const std::vector<std::string> files = map_files(args, sector_estimators);
  if (!polygon_maps(files, sector_estimators)) {
    throw Error(
        "the sector protocol needs polygon maps (--maps polygons/office or a polygon YAML; "
        "maps/README.md, Polygon map format)");
  }
  run_sectors(args, files);
}

/// Seed 001's protocol; throws on polygon maps or a sector estimator (the sector protocol's).
void run_grid_protocol(const EvalArgs& args, bool laser) {
  check_step(args.step_xy);
  if (names_a_sector_estimator(args.estimators)) {
    throw Error("the sectors estimators run the sector protocol: gridloc eval sectors");
  }
  const std::vector<std::string> files = map_files(args, false);
  if (polygon_maps(files, false)) {
    throw Error("polygon maps run the sector protocol: gridloc eval sectors --maps ...");
  }
  EvalArgs chosen = args;
  chosen.laser.enabled = laser;
  run_seed_001(chosen, files);
}

}  // namespace

std::string protocol_name(EvalProtocol protocol) {
  switch (protocol) {
    case EvalProtocol::Sonar:
      return "sonar";
    case EvalProtocol::Laser:
      return "laser";
    case EvalProtocol::Drive:
      return "drive";
    case EvalProtocol::Sectors:
      return "sectors";
    case EvalProtocol::Disambiguation:
      return "disambiguation";
    case EvalProtocol::Team:
      return "team";
  }
  return "sonar";
}

EvalProtocol old_spelling_protocol(const EvalArgs& args, const DriveArgs& drive,
                                   const ProtocolArgs& protocol) {
  if (protocol.name == "disambiguation") return EvalProtocol::Disambiguation;
  if (protocol.name == "team") return EvalProtocol::Team;
  if (drive.given) return EvalProtocol::Drive;  // run_drive checks its maps and estimators
  check_step(args.step_xy);
  const bool sector_estimators = names_a_sector_estimator(args.estimators);
  const std::vector<std::string> files = map_files(args, sector_estimators);
  if (polygon_maps(files, sector_estimators)) return EvalProtocol::Sectors;
  return args.laser.enabled ? EvalProtocol::Laser : EvalProtocol::Sonar;
}

void run_protocol(EvalProtocol protocol, const EvalArgs& args, const DriveArgs& drive,
                  const ProtocolArgs& protocol_args) {
  switch (protocol) {
    case EvalProtocol::Disambiguation:
      return run_disambiguation(args, drive, protocol_args);
    case EvalProtocol::Team:
      return run_team(args, drive, protocol_args);
    case EvalProtocol::Drive:
      return run_drive(args, drive);
    case EvalProtocol::Sectors:
      return run_sector_protocol(args);
    case EvalProtocol::Sonar:
      return run_grid_protocol(args, false);
    case EvalProtocol::Laser:
      return run_grid_protocol(args, true);
  }
}

}  // namespace gridloc::cli
