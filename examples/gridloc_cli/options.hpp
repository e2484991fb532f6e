#pragma once
// Parsing helpers shared by the gridloc subcommands.
#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/octomap_io.hpp"
#include "gridloc/sensors/odometry_noise.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc::cli {

/// Parses "x,y,theta" (metres, metres, radians); throws gridloc::Error naming `what`.
Pose2 parse_pose(const std::string& text, const std::string& what);

LocalModel parse_local(const std::string& text);
GlobalModel parse_global(const std::string& text);
/// The evaluations' --noise: "realistic" (SonarSimOptions::realistic) or "none".
SonarSimOptions parse_noise(const std::string& text);
/// FRAC,DEG_PER_M of --odometry-noise (length share, heading drift in degrees per metre).
OdometryNoise parse_odometry_noise(const std::string& text,
                                   const std::string& option = "--odometry-noise");
SearchStrategy parse_strategy(const std::string& text);
ArcRule parse_arc_rule(const std::string& text);
ScanModel parse_scan_model(const std::string& text);
std::string to_string(ArcRule rule);
/// Checks --arc-depth (cells, >= 0, finite).
double check_arc_depth(double cells);

/// Throws "<flag> <rule>, got <value>" unless `ok`: every command's check of a number has
/// this one form (the library's require_option names its owner and field the same way).
void require_flag(bool ok, std::string_view flag, double value, std::string_view rule);

/// The search options `localize` and `eval` share: registered once, applied once.
struct SearchArgs {
  std::string strategy = "bnb";
  std::string arc_rule = "neutral";
  double arc_depth = SonarModelOptions{}.arc_depth_cells;
  int threads = 1;
  std::string scan_model = "hits";
  int free_samples = ScanModelOptions{}.free_samples;
  double budget_ms = 0.0;
  bool heading_intervals = false;
  bool no_second_peak = false;
  double second_peak_floor = CorrelationOptions{}.second_peak_floor;
  int hypotheses = CorrelationOptions{}.hypotheses;
  int covariance_cells = CorrelationOptions{}.covariance_cells;
  double covariance_temperature = CorrelationOptions{}.covariance_temperature;
  double ring_covariance_temperature = CorrelationOptions{}.ring_covariance_temperature;
  double scan_quantization_share = CorrelationOptions{}.scan_quantization_share;
  double ring_quantization_share = CorrelationOptions{}.ring_quantization_share;
  bool covariance_peaks = CorrelationOptions{}.covariance_spans_peaks;  ///< --covariance-peaks
  bool rising_edge_check = VerdictOptions{}.rising_edge_not_localized;  ///< --rising-edge-check

  /// Adds --strategy, --arc-rule, --arc-depth, --threads, --scan-model, --free-samples,
  /// --budget-ms, --heading-intervals, --no-second-peak, --hypotheses and
  /// --covariance-cells.
  void add_to(CLI::App* cmd);
  /// Parses and checks them into `options`; throws gridloc::Error naming the option.
  void apply(CorrelationOptions& options) const;
};

/// The height band of an OctoMap map: --octomap-z-min, --octomap-z-max (m); used only when
/// the map is a .bt/.ot file.
struct OctomapArgs {
  OctomapSlice slice;
  /// Adds --octomap-z-min and --octomap-z-max.
  void add_to(CLI::App* cmd);
};

/// The file to read for a map option (`option` names it in errors): `path`, or for `-` the
/// copy of standard input, named .bt or .ot when its first line is an OctoMap's, else .yaml
/// (the loaders tell a map's kind by its extension first).
std::string map_input_path(const std::string& path, const std::string& option = "--map");

/// True when the map of `path` (`-`: standard input) is a polygon map (a YAML with a
/// `boundary`), not an OctoMap or a map_server YAML.
bool is_polygon_map_input(const std::string& path, const std::string& option = "--map");

/// A map_server map; from `-` (standard input) its relative `image:` is relative to the
/// current folder.
OccupancyMap load_ros_map_input(const std::string& path, const std::string& option = "--map");

/// Loads a map by its kind: an OctoMap tree (.bt, .ot) sliced to the band of `slice`
/// (load_octomap), a polygon map rasterized at its own resolution, otherwise a map_server
/// YAML (load_ros_map_input). `path` may be `-` (standard input; `option` names it).
OccupancyMap load_map(const std::string& path, const OctomapSlice& slice = {},
                      const std::string& option = "--map");

/// Folder of the bundled maps: $GRIDLOC_DATA_DIR, else the source tree's maps/, else the
/// installed share/gridloc/maps.
std::string data_dir();

}  // namespace gridloc::cli
