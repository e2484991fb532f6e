#include "localization_args.hpp"
#include "limit_options.hpp"

#include <chrono>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/echo_filter.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/readings_io.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

/// Throws gridloc::Error naming `flag` unless `options` (one field set) are valid.
void check_field(const char* flag, const LikelihoodFieldOptions& options) {
  try {
    options.validate();
  } catch (const Error& e) {
    throw Error(std::string(flag) + ": " + e.what());
  }
}

}  // namespace

void FieldArgs::add_to(CLI::App* cmd) {
  cmd->add_option("--field-sigma", field.sigma_m,
                  "--global-grid field: spread of the field around walls (m), exp(-d^2 / 2 "
                  "sigma^2)")
      ->capture_default_str();
  cmd->add_option("--field-cutoff", field.cutoff_m,
                  "--global-grid field: the field reaches this far from a wall (m); free cells "
                  "beyond score --field-free")
      ->capture_default_str();
  cmd->add_option("--field-free", field.free_value,
                  "--global-grid field: value of free cells beyond the cutoff, in [-1, 0] "
                  "(free-space evidence; 0 = none)")
      ->capture_default_str();
}

void FieldArgs::apply(CorrelationOptions& options) const {
  LikelihoodFieldOptions one;
  one.sigma_m = field.sigma_m;
  check_field("--field-sigma", one);
  one = {};
  one.cutoff_m = field.cutoff_m;
  check_field("--field-cutoff", one);
  one = {};
  one.free_value = field.free_value;
  check_field("--field-free", one);
  options.field = field;
}

void LocalizationArgs::add_to(CLI::App* cmd, const std::string& global_help) {
  if (ring.empty()) ring = data_dir() + "/sensors/wheelchair_14.yaml";
  cmd->add_option("--map", map,
                  "map_server YAML (or OctoMap .bt/.ot, or polygon YAML) of the known map (- "
                  "reads standard input)")
      ->required();
  octomap.add_to(cmd);
  cmd->add_option("--ring", ring, "sonar ring YAML (- reads standard input)")
      ->capture_default_str();
  cmd->add_option("--readings", readings,
                  "sonar readings JSON {\"ranges_m\": [...]} (- reads standard input)");
  cmd->add_option("--scan", scan,
                  "laser/IR scan CSV: angle_rad,range_m per line (- reads standard input)");
  cmd->add_option("--max-range", max_range, "scan max range (m); longer ranges are no return")
      ->capture_default_str();
  cmd->add_option("--prior", prior, "prior pose x,y,theta (m, m, rad)");
  cmd->add_flag("--global", whole_map, global_help);
  cmd->add_option("--window-xy", window.half_xy, "half width of the search square (m)")
      ->capture_default_str();
  cmd->add_option("--window-theta", window.half_theta, "half width of the heading cone (rad)")
      ->capture_default_str();
  cmd->add_option("--step-xy", window.step_xy,
                  "translation step = grid cell (m); with --scan the map's cell by default")
      ->capture_default_str()
      ->each([this](const std::string&) { step_xy_given = true; });
  cmd->add_option("--step-theta", window.step_theta,
                  "heading step (rad); with --scan by default the step that moves the farthest "
                  "return by half a cell (one cell under --global)")
      ->capture_default_str()
      ->each([this](const std::string&) { step_theta_given = true; });
  cmd->add_option("--local", local, "local grid: oriented | turned")->capture_default_str();
  cmd->add_option("--global-grid,--global-model", global,
                  "global grid: thinned | raw | field (likelihood field, see --field-sigma)")
      ->capture_default_str();
  field.add_to(cmd);
  cmd->add_option("--levels", levels, "multiresolution levels")->capture_default_str();
  search.add_to(cmd);
}

Localization prepare_localization(const LocalizationArgs& args,
                                  const std::function<void(CorrelationOptions&)>& tune) {
  using clock = std::chrono::steady_clock;
  if (args.whole_map == !args.prior.empty())
    throw Error("give either --prior x,y,theta or --global");
  if (args.readings.empty() == args.scan.empty()) {
    throw Error("give either --readings (sonar ring) or --scan (laser/IR scan CSV)");
  }
  Localization localization;
  std::vector<std::vector<double>> firings;
  if (args.scan.empty()) {
    firings = load_firings(input_path(args.readings, "--readings"), limits());
    localization.firings = static_cast<int>(firings.size());
    localization.observation.ranges = firings.front();
  } else {
    localization.observation.scan =
        load_scan_csv(input_path(args.scan, "--scan"), args.max_range, limits());
  }
  const auto t0 = clock::now();
  OccupancyMap map = load_map(args.map, args.octomap.slice);
  const bool scan_defaults = localization.observation.scan.has_value();
  localization.window = args.window;
  if (scan_defaults && !args.step_xy_given) localization.window.step_xy = map.geometry.resolution;
  CorrelationOptions options;
  options.local = parse_local(args.local);
  options.global = parse_global(args.global);
  args.search.apply(options);
  args.field.apply(options);
  options.resolution = localization.window.step_xy;
  options.levels = args.levels;
  options.limits = limits();
  // A scan needs no ring: the padding covers its max range instead.
  options.reach_m = localization.observation.scan ? args.max_range : 0.0;
  // A window needs the bound pyramid only as deep as it is wide: less to precompute.
  if (!args.whole_map) options.max_bound_depth = window_bound_depth(localization.window);
  if (tune) tune(options);
  if (localization.observation.scan) {
    localization.estimator = std::make_unique<CorrelationEstimator>(std::move(map), options);
  } else {
    SonarRing ring = load_sonar_ring(input_path(args.ring, "--ring"), limits());
    if (firings.size() > 1) {  // consecutive firings: keep the echoes they repeat
      FilteredReadings filtered = filter_echoes(ring, firings);
      localization.observation.ranges = std::move(filtered.ranges);
      localization.observation.rejected = std::move(filtered.rejected);
    }
    localization.estimator =
        std::make_unique<CorrelationEstimator>(std::move(map), std::move(ring), options);
  }
  localization.precompute_ms = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  const SearchWindow whole = localization.estimator->global_window(localization.observation);
  if (args.whole_map) {
    localization.window = whole;
    if (args.step_theta_given) localization.window.step_theta = args.window.step_theta;
  } else {
    localization.window.center = parse_pose(args.prior, "--prior");
    // Half the global search's step: the farthest return moves by half a cell. On the
    // apartment bench case a whole cell's step left case 1 0.40 deg off, half of it 0.07 deg.
    if (scan_defaults && !args.step_theta_given) {
      localization.window.step_theta = 0.5 * whole.step_theta;
    }
  }
  return localization;
}

}  // namespace gridloc::cli
