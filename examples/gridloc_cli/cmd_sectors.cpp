// gridloc sectors: the visibility sectors of a polygon map (seed 000 §2) as seed 000's Table 1
// (each sector's label of characteristic points) with the readings per turn it needs
// (eqs. 10-11) and which labels a scan cannot tell apart (§4.1); optionally an image and JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gridloc/engine/sectors/sector_file.hpp"
#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "output_files.hpp"
#include "plot.hpp"
#include "sectors_render.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

struct SectorsArgs {
  std::string polygons, out;
  double cell_m = SectorOptions{}.cell_m;
  bool json = false;
};

int ambiguous_count(const SectorMap& sectors) {
  return static_cast<int>(std::count_if(sectors.sectors.begin(), sectors.sectors.end(),
                                        [](const Sector& sector) { return sector.ambiguous; }));
}

nlohmann::json sectors_json(const SectorsArgs& args, const SectorMap& sectors) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < sectors.sectors.size(); ++k) {
    const Sector& sector = sectors.sectors[k];
    // Visible vertices as coordinates: indices would need the vertex list to mean anything.
    nlohmann::json visible = nlohmann::json::array();
    for (int vertex : sector.visible)
      visible.push_back({sectors.vertices[vertex].x(), sectors.vertices[vertex].y()});
    rows.push_back(
        {{"id", k + 1},
         {"label", sector.label},
         {"area_m2", sector.area_m2},
         {"representative", {{"x", sector.representative.x()}, {"y", sector.representative.y()}}},
         {"ambiguous", sector.ambiguous},
         {"n_min", sector.n_min},
         {"n_min_two", sector.n_min_two},
         {"visible_vertices", visible}});
  }
  return {{"polygons", args.polygons},
          {"cell_m", args.cell_m},
          {"sectors", rows},
          {"sector_count", sectors.sectors.size()},
          {"ambiguous_count", ambiguous_count(sectors)},
          {"n_min_two", sectors.n_min_two()}};
}

/// Seed 000's Table 1 with the area, where the label was read, and the readings per turn.
void print_table(const SectorsArgs& args, const SectorMap& sectors) {
  std::size_t label_width = 5;
  for (const Sector& sector : sectors.sectors)
    label_width = std::max(label_width, sector.label.size());
  const int label_columns = static_cast<int>(label_width);
  std::printf("Visibility sectors of %s (%.3g m cells)\n", args.polygons.c_str(), args.cell_m);
  std::printf("%4s  %-*s  %8s  %-16s  %-9s  %7s  %9s\n", "Sec.", label_columns, "Label", "Area m2",
              "Representative", "Ambiguous", "n_min", "n_min_two");
  bool unreachable = false;
  for (std::size_t k = 0; k < sectors.sectors.size(); ++k) {
    const Sector& sector = sectors.sectors[k];
    char where[48];
    std::snprintf(where, sizeof where, "(%.2f, %.2f)", sector.representative.x(),
                  sector.representative.y());
    // 0 readings means no cell of the sector is clear of the walls: print "-", not 0.
    const std::string n_min = sector.n_min > 0 ? std::to_string(sector.n_min) : "-";
    const std::string n_min_two = sector.n_min_two > 0 ? std::to_string(sector.n_min_two) : "-";
    unreachable = unreachable || sector.n_min == 0;
    std::printf("%4zu  %-*s  %8.2f  %-16s  %-9s  %7s  %9s\n", k + 1, label_columns,
                sector.label.empty() ? "-" : sector.label.c_str(), sector.area_m2, where,
                sector.ambiguous ? "yes" : "no", n_min.c_str(), n_min_two.c_str());
  }
  std::printf(
      "%zu sector%s, %d ambiguous (label equal to another's up to a turn, seed 000 4.1); "
      "N'_min %d readings per turn (seed 000 eq. 11)\n",
      sectors.sectors.size(), sectors.sectors.size() == 1 ? "" : "s", ambiguous_count(sectors),
      sectors.n_min_two());
  if (unreachable) {
    std::printf("n_min '-': no cell of the sector is %.2f m from the walls\n",
                SectorOptions{}.clearance_m);
  }
}

void run(const SectorsArgs& args) {
  require_flag(args.cell_m > 0.0 && std::isfinite(args.cell_m), "--cell", args.cell_m,
               "must be a positive cell size in metres");
  const PolygonMap map = load_polygon_map(input_path(args.polygons, "--polygons"), limits());
  // The folder first: a bad --out fails before the sectors are computed.
  if (!args.out.empty()) output_folder(args.out);
  SectorOptions options;
  options.cell_m = args.cell_m;
  options.limits = limits();
  const SectorMap sectors = compute_sectors(map, options);
  const nlohmann::json out = sectors_json(args, sectors);

  std::string written;
  if (!args.out.empty()) {
    const fs::path dir(args.out);
    const std::string json_path = (dir / "sectors.json").string();
    const std::string png_path = (dir / "sectors.png").string();
    const std::string saved_path = (dir / "sector_map.json").string();
    save_sectors(sectors, options, saved_path);  // for localize --sectors
    write_json_file(json_path, out, "the sectors");
    plot::write_png(png_path, render_sectors(sectors, fs::path(args.polygons).filename().string()));
    written = "wrote " + png_path + ", " + json_path + " and " + saved_path + "\n";
  }
  // stdout stays pure JSON with --json; the files are where --out said.
  if (args.json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  print_table(args, sectors);
  std::cout << written;
}

}  // namespace

void add_sectors(CLI::App& app) {
  auto args = std::make_shared<SectorsArgs>();
  auto* cmd = app.add_subcommand(
      "sectors", "Visibility sectors of a polygon map and their labels (seed 000 Table 1)");
  cmd->add_option("--polygons", args->polygons,
                  "polygon map (YAML with a 'boundary'; - reads standard input)")
      ->required();
  cmd->add_option("--out", args->out,
                  "folder for sectors.png, sectors.json and sector_map.json (the sectors, for "
                  "localize --sectors; created if missing)");
  cmd->add_option("--cell", args->cell_m,
                  "sampling cell of the free space (m): smaller finds thinner sectors, slower")
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print JSON instead of the table");
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
