#include "options.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {

Pose2 parse_pose(const std::string& text, const std::string& what) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw Error(what + ": '" + text + "' is not x,y,theta (numbers)");
    }
  }
  if (values.size() != 3) throw Error(what + ": '" + text + "' must be three numbers x,y,theta");
  for (double value : values) {
    if (!std::isfinite(value)) throw Error(what + ": '" + text + "' must be finite");
  }
  return {values[0], values[1], values[2]};
}

LocalModel parse_local(const std::string& text) {
  if (text == "oriented") return LocalModel::Oriented;
  if (text == "turned") return LocalModel::Turned;
  throw Error("--local must be oriented or turned, not '" + text + "'");
}

SonarSimOptions parse_noise(const std::string& text) {
  if (text == "realistic") return SonarSimOptions::realistic(1);
  if (text == "none") return SonarSimOptions{};
  throw Error("--noise must be realistic or none, not '" + text + "'");
}

OdometryNoise parse_odometry_noise(const std::string& text, const std::string& option) {
  OdometryNoise noise;
  std::vector<double> fields;
  try {
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = text.find(',', from);
      const std::string field =
          text.substr(from, comma == std::string::npos ? comma : comma - from);
      std::size_t used = 0;
      fields.push_back(std::stod(field, &used));
      if (used != field.size()) throw std::invalid_argument(text);
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    if (fields.size() < 2 || fields.size() > 3) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw Error(option +
                " must be FRAC,DEG_PER_M or FRAC,DEG_PER_M,SLIP_EVERY_M (e.g. 0.02,1 or "
                "0.05,5,50), not '" +
                text + "'");
  }
  noise.frac = fields[0];
  noise.rad_per_m = deg2rad(fields[1]);
  if (fields.size() == 3) noise.slip_every_m = fields[2];
  return noise;
}

GlobalModel parse_global(const std::string& text) {
  if (text == "thinned") return GlobalModel::Thinned;
  if (text == "raw") return GlobalModel::Raw;
  if (text == "field") return GlobalModel::LikelihoodField;
  throw Error("--global-grid must be thinned, raw or field, not '" + text + "'");
}

SearchStrategy parse_strategy(const std::string& text) {
  for (SearchStrategy strategy :
       {SearchStrategy::BranchAndBound, SearchStrategy::Exhaustive, SearchStrategy::Multires}) {
    if (text == to_string(strategy)) return strategy;
  }
  throw Error("--strategy must be bnb, exhaustive or multires, not '" + text + "'");
}

ArcRule parse_arc_rule(const std::string& text) {
  if (text == "neutral") return ArcRule::Neutral;
  if (text == "signed") return ArcRule::Signed;
  throw Error("--arc-rule must be neutral or signed, not '" + text + "'");
}

std::string to_string(ArcRule rule) {
  return rule == ArcRule::Neutral ? "neutral" : "signed";
}

ScanModel parse_scan_model(const std::string& text) {
  for (ScanModel model : {ScanModel::Hits, ScanModel::Samples, ScanModel::Rays}) {
    if (text == to_string(model)) return model;
  }
  throw Error("--scan-model must be hits, samples or rays, not '" + text + "'");
}

void require_flag(bool ok, std::string_view flag, double value, std::string_view rule) {
  if (ok) return;
  throw Error(std::string(flag) + " " + std::string(rule) + ", got " + message_number(value));
}

double check_arc_depth(double cells) {
  require_flag(cells >= 0.0 && std::isfinite(cells), "--arc-depth", cells,
               "must be a finite number of cells >= 0");
  return cells;
}

void SearchArgs::add_to(CLI::App* cmd) {
  cmd->add_option("--strategy", strategy,
                  "bnb (exact branch and bound, fastest exact) | exhaustive (exact) | multires "
                  "(seed 001's coarse-to-fine, not exact)")
      ->capture_default_str();
  cmd->add_option("--arc-rule", arc_rule, "arc cell on free space: neutral | signed (seed 001)")
      ->capture_default_str();
  cmd->add_option("--arc-depth", arc_depth, "radial arc depth, cells each side (0 = seed 001)")
      ->capture_default_str();
  cmd->add_option("--threads", threads, "threads scoring headings in parallel (same result)")
      ->capture_default_str();
  cmd->add_option("--scan-model", scan_model,
                  "scan local grid: hits (end cells only) | samples (end cells + free samples) "
                  "| rays (end cells + every crossed cell)")
      ->capture_default_str();
  cmd->add_option("--free-samples", free_samples, "free samples per beam (--scan-model samples)")
      ->capture_default_str();
  cmd->add_option("--budget-ms", budget_ms,
                  "bnb: stop after this many ms with the best pose so far (0 = no limit); "
                  "stats.proven_optimal says whether it is the optimum")
      ->capture_default_str();
  cmd->add_flag(
      "--heading-intervals", heading_intervals,
      "bnb with a scan: bound intervals of headings too (exact; see engine/doc/correlation.md)");
  cmd->add_option("--hypotheses", hypotheses,
                  "distinct poses to report in alternatives, the winner included (found "
                  "exactly by bnb, one search each)")
      ->capture_default_str();
  cmd->add_option("--covariance-cells", covariance_cells,
                  "covariance from the poses within this many cells and heading steps of the "
                  "winner (0 = none)")
      ->capture_default_str();
  cmd->add_option("--covariance-temperature", covariance_temperature,
                  "the covariance weighs each pose by exp((score - best) / this); the verdict "
                  "reads its spread")
      ->capture_default_str();
  cmd->add_option("--ring-covariance-temperature", ring_covariance_temperature,
                  "a sonar ring's answer reports the covariance at this temperature instead "
                  "(0 = --covariance-temperature); no verdict changes with it")
      ->capture_default_str();
  cmd->add_option("--scan-quantization-share", scan_quantization_share,
                  "a scan's refined pose reports this share of the lattice's quantization "
                  "variance (1 = all of it, as before); no verdict changes with it")
      ->capture_default_str();
  cmd->add_option("--ring-quantization-share", ring_quantization_share,
                  "a sonar ring's refined pose reports this share of the lattice's "
                  "quantization variance (1 = all of it); no verdict changes with it")
      ->capture_default_str();
  cmd->add_option("--covariance-peaks", covariance_peaks,
                  "true: the reported covariance also spans the window's other peaks "
                  "(alternatives) weighted at its temperature, as a corridor's doors make them; "
                  "no verdict changes with it (default true for relations)")
      ->capture_default_str();
  cmd->add_option("--rising-edge-check", rising_edge_check,
                  "true: an answer on the window's edge whose score still rises one and two "
                  "steps past it (JSON rises_past_window_edge: the truth is likely outside "
                  "the window) is not localized; false: it keeps its verdict")
      ->capture_default_str();
  cmd->add_flag("--no-second-peak", no_second_peak,
                "bnb: skip the exact search for the best distinct pose (faster; the "
                "confidence is then optimistic)");
  cmd->add_option("--second-peak-floor", second_peak_floor,
                  "bnb: look for the hypotheses after the winner only among poses scoring at "
                  "least this share of it (0: all, exact second_score; below the floor "
                  "second_score is the floor and second_below_floor true)")
      ->capture_default_str();
}

void SearchArgs::apply(CorrelationOptions& options) const {
  options.strategy = parse_strategy(strategy);
  options.arc_rule = parse_arc_rule(arc_rule);
  options.sonar.arc_depth_cells = check_arc_depth(arc_depth);
  options.threads = threads;
  options.scan.model = parse_scan_model(scan_model);
  options.scan.free_samples = free_samples;
  require_flag(budget_ms >= 0.0 && std::isfinite(budget_ms), "--budget-ms", budget_ms,
               "must be a finite number >= 0");
  if (options.strategy != SearchStrategy::BranchAndBound &&
      (budget_ms > 0.0 || heading_intervals)) {
    throw Error(std::string(budget_ms > 0.0 ? "--budget-ms" : "--heading-intervals") +
                " needs --strategy bnb");
  }
  options.budget_ms = budget_ms;
  options.heading_intervals = heading_intervals;
  options.second_peak = !no_second_peak;
  require_flag(second_peak_floor >= 0.0 && second_peak_floor < 1.0, "--second-peak-floor",
               second_peak_floor, "must lie in [0, 1)");
  options.second_peak_floor = second_peak_floor;
  require_flag(hypotheses >= 1 && hypotheses <= 100, "--hypotheses", hypotheses,
               "must lie in [1, 100]");
  options.hypotheses = hypotheses;
  require_flag(covariance_cells >= 0 && covariance_cells <= 20, "--covariance-cells",
               covariance_cells, "must lie in [0, 20]");
  options.covariance_cells = covariance_cells;
  options.covariance_temperature = covariance_temperature;
  options.ring_covariance_temperature = ring_covariance_temperature;
  require_flag(scan_quantization_share >= 0.0 && scan_quantization_share <= 1.0,
               "--scan-quantization-share", scan_quantization_share, "must lie in [0, 1]");
  options.scan_quantization_share = scan_quantization_share;
  require_flag(ring_quantization_share >= 0.0 && ring_quantization_share <= 1.0,
               "--ring-quantization-share", ring_quantization_share, "must lie in [0, 1]");
  options.ring_quantization_share = ring_quantization_share;
  options.covariance_spans_peaks = covariance_peaks;
  options.verdict.rising_edge_not_localized = rising_edge_check;
  // Checked whatever the model: a bad number is a mistake even where it is not used.
  require_flag(free_samples >= 1 && free_samples <= 1000, "--free-samples", free_samples,
               "must lie in [1, 1000]");
}

void OctomapArgs::add_to(CLI::App* cmd) {
  cmd->add_option("--octomap-z-min", slice.z_min,
                  "OctoMap map (.bt/.ot): lower edge of the height band sliced into the 2-D map "
                  "(m)")
      ->capture_default_str();
  cmd->add_option("--octomap-z-max", slice.z_max,
                  "OctoMap map (.bt/.ot): upper edge of the height band (m)")
      ->capture_default_str();
}

namespace {

/// The extension of the OctoMap whose first line is `first_line` (".bt" or ".ot"), or "".
std::string octomap_extension_of(const std::string& first_line) {
  if (first_line.rfind("# Octomap OcTree binary file", 0) == 0) return ".bt";
  if (first_line.rfind("# Octomap OcTree file", 0) == 0) return ".ot";
  return "";
}

}  // namespace

std::string map_input_path(const std::string& path, const std::string& option) {
  const std::string file = input_path(path, option);
  if (path != kStdin) return file;
  // Any other map is a YAML (map_server or polygon): is_polygon_map_file wants its extension.
  const std::string extension = octomap_extension_of(stdin_first_line());
  return stdin_path_with_extension(extension.empty() ? ".yaml" : extension);
}

bool is_polygon_map_input(const std::string& path, const std::string& option) {
  const std::string file = map_input_path(path, option);
  return !is_octomap_path(file) && is_polygon_map_file(file, limits());
}

OccupancyMap load_ros_map_input(const std::string& path, const std::string& option) {
  const std::string file = input_path(path, option);
  // A YAML over kMaxMapYamlBytes is refused by load_ros_map before it is read whole.
  if (path != kStdin || check_input_file(file, "map YAML", limits()) > kMaxMapYamlBytes) {
    return load_ros_map(file, limits());
  }
  return load_ros_map_text(read_input_file(file, "map YAML", limits()), "standard input",
                           std::filesystem::current_path().string(), limits());
}

OccupancyMap load_map(const std::string& path, const OctomapSlice& slice,
                      const std::string& option) {
  const std::string file = map_input_path(path, option);
  if (is_octomap_path(file)) return load_octomap(file, slice, limits());
  // A polygon map (a YAML file with a `boundary`) is rasterized at its own resolution.
  if (is_polygon_map_file(file, limits())) {
    return rasterize_polygon_map(load_polygon_map(file, limits()), 0.0, 0.5, limits());
  }
  return load_ros_map_input(path, option);
}

std::string data_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("GRIDLOC_DATA_DIR")) return env;
  if (fs::exists(GRIDLOC_SOURCE_MAPS_DIR)) return GRIDLOC_SOURCE_MAPS_DIR;
  // Installed under any prefix: <prefix>/bin/gridloc finds <prefix>/share/gridloc/maps.
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = exe.parent_path().parent_path() / "share" / "gridloc" / "maps";
    if (fs::exists(beside)) return beside.string();
  }
  return GRIDLOC_INSTALL_MAPS_DIR;
}

}  // namespace gridloc::cli
