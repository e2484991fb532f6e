// gridloc map-from-log: an occupancy map drawn from a SLAM-corrected CARMEN log by ray casting
// at its logged laser poses, from all its scans or from one part of alternate blocks (issue
// 13's real-data evaluation: the map from one part, the other localized against it).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/log_map.hpp"
#include "gridloc/sensors/log_split.hpp"
#include "limit_options.hpp"
#include "old_spelling.hpp"
#include "plot.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

struct MapFromLogArgs {
  std::string log, out, part = "all";
  LogSplitOptions split;
  LogMapOptions map;
  bool png = false;
  bool json = false;
};

/// The scans of the part asked for.
const std::vector<std::size_t>& part_scans(const LogSplit& split, const std::string& part) {
  return part == "held-out" ? split.held_out : split.map;
}

/// The map as an image, north up, in save_ros_map's greys (black occupied, white free).
void write_png(const OccupancyMap& map, const std::string& path) {
  cv::Mat img(map.height(), map.width(), CV_8UC1);
  for (int iy = 0; iy < map.height(); ++iy) {
    auto* px = img.ptr<std::uint8_t>(map.height() - 1 - iy);
    for (int ix = 0; ix < map.width(); ++ix) {
      const CellState s = map.at(ix, iy);
      px[ix] = s == CellState::Occupied ? 0 : s == CellState::Free ? 254 : 205;
    }
  }
  plot::write_png(path, img);
}

nlohmann::json summary(const MapFromLogArgs& args, std::size_t scans, const LogSplit& split,
                       const OccupancyMap& map) {
  const CellCounts cells = count_cells(map);
  const GridGeometry& g = map.geometry;
  nlohmann::json files = {{"yaml", args.out},
                          {"pgm", fs::path(args.out).replace_extension(".pgm").string()}};
  if (args.png) files["png"] = fs::path(args.out).replace_extension(".png").string();
  return {
      {"log", args.log},
      {"scans", scans},
      {"part", args.part},
      {"split",
       {{"rule", to_string(split.rule)},
        {"block_s", args.split.block_s},
        {"block_scans", args.split.block_scans},
        {"blocks", split.blocks},
        {"map_scans", split.map.size()},
        {"held_out_scans", split.held_out.size()},
        {"timestamps_unusable", split.timestamps_unusable}}},
      {"scans_used", part_scans(split, args.part).size()},
      {"map",
       {{"resolution", g.resolution},
        {"width", g.width},
        {"height", g.height},
        {"width_m", g.width * g.resolution},
        {"height_m", g.height * g.resolution},
        {"origin", {g.origin.x(), g.origin.y()}}}},
      {"cells", {{"occupied", cells.occupied}, {"free", cells.free}, {"unknown", cells.unknown}}},
      {"files", files}};
}

void print_summary(const nlohmann::json& s) {
  const nlohmann::json& split = s["split"];
  std::string rule = split["rule"].get<std::string>();
  if (rule != "all") {
    rule += " (" + std::to_string(split["blocks"].get<std::size_t>()) + " blocks; map part " +
            std::to_string(split["map_scans"].get<std::size_t>()) + ", held-out part " +
            std::to_string(split["held_out_scans"].get<std::size_t>()) + " scans)";
  }
  std::printf("map from %s: %zu of %zu scans (part %s, split: %s)\n",
              s["log"].get<std::string>().c_str(), s["scans_used"].get<std::size_t>(),
              s["scans"].get<std::size_t>(), s["part"].get<std::string>().c_str(), rule.c_str());
  if (!split["timestamps_unusable"].get<std::string>().empty()) {
    std::printf("timestamps not used: %s\n",
                split["timestamps_unusable"].get<std::string>().c_str());
  }
  const nlohmann::json& m = s["map"];
  std::printf("map %d x %d cells (%.2f m x %.2f m at %.3g m), %zu occupied, %zu free; wrote %s\n",
              m["width"].get<int>(), m["height"].get<int>(), m["width_m"].get<double>(),
              m["height_m"].get<double>(), m["resolution"].get<double>(),
              s["cells"]["occupied"].get<std::size_t>(), s["cells"]["free"].get<std::size_t>(),
              s["files"]["yaml"].get<std::string>().c_str());
}

void run(const MapFromLogArgs& args) {
  if (args.out.empty()) {
    throw Error("--map-out is required: the map_server YAML to write (old spelling --out)");
  }
  LogMapOptions map_options = args.map;
  map_options.limits = limits();
  validate(map_options);  // before the log is read: a bad option is reported first
  validate(args.split);
  CarmenOptions carmen;
  carmen.limits = limits();
  const CarmenLog log = load_carmen_log(input_path(args.log, "--log"), carmen);
  const LogSplit split =
      args.part == "all" ? all_scans(log.lasers) : split_log(log.lasers, args.split);
  const std::vector<std::size_t>& scans = part_scans(split, args.part);
  if (scans.empty()) {
    throw Error(input_path(args.log, "--log") + ": the " + args.part + " part holds no scan (" +
                std::to_string(split.blocks) + " block(s) of " + to_string(split.rule) + ")");
  }
  const OccupancyMap map = map_from_log(log, scans, map_options);
  save_ros_map(map, args.out);
  if (args.png) write_png(map, fs::path(args.out).replace_extension(".png").string());
  const nlohmann::json out = summary(args, log.lasers.size(), split, map);
  if (args.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_summary(out);
  }
}

}  // namespace

void add_map_from_log(CLI::App& app) {
  auto args = std::make_shared<MapFromLogArgs>();
  auto* cmd = app.add_subcommand(
      "map-from-log",
      "Draw an occupancy map from a SLAM-corrected CARMEN log (ray casting at its laser poses)");
  cmd->add_option("--log", args->log,
                  "CARMEN log, plain or gzip (FLASER / ROBOTLASER1 lines; - reads standard input)")
      ->required();
  // --out is the old spelling (kept, out of --help): --out names a folder elsewhere.
  cmd->add_option("--map-out", args->out, "map_server YAML to write (the PGM goes beside it)");
  cmd->add_option("--out", args->out, "old spelling of --map-out")->group(kOldSpelling);
  hide_old_spellings(cmd);
  cmd->add_option("--part", args->part,
                  "all: every scan; map: the even blocks of the split; held-out: the odd ones")
      ->check(CLI::IsMember({"all", "map", "held-out"}))
      ->capture_default_str();
  cmd->add_option("--block-s", args->split.block_s, "split: block length (s) by time")
      ->capture_default_str();
  cmd->add_option("--block-scans", args->split.block_scans,
                  "split: block length (scans) when the timestamps are unusable")
      ->capture_default_str();
  cmd->add_option("--resolution", args->map.resolution, "cell size (m)")->capture_default_str();
  cmd->add_option("--max-range", args->map.max_range_m, "farther returns count as no return (m)")
      ->capture_default_str();
  cmd->add_option("--no-return-free", args->map.no_return_free_m,
                  "beams without return are drawn free up to this distance (m; 0: skipped)")
      ->capture_default_str();
  cmd->add_option("--occupied-ratio", args->map.occupied_ratio,
                  "a cell is occupied when hits / (hits + passes) reaches this")
      ->capture_default_str();
  cmd->add_option("--min-hits", args->map.min_hits, "a cell is occupied after this many hits")
      ->capture_default_str();
  cmd->add_flag("--png", args->png, "also write the map as a PNG beside the YAML");
  cmd->add_flag("--json", args->json, "print the summary as JSON");
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
