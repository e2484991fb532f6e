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
#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "heatmap_plot.hpp"
#include "sectors_render.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

struct SectorsArgs {
  std::string polygons, out;
  double cell_m = SectorOptions{}.cell_m;
  bool json = false;
};

int ambiguous_count(const SectorMap& s) {
  return static_cast<int>(std::count_if(s.sectors.begin(), s.sectors.end(),
                                        [](const Sector& x) { return x.ambiguous; }));
}

nlohmann::json sectors_json(const SectorsArgs& a, const SectorMap& s) {
  nlohmann::json sectors = nlohmann::json::array();
  for (std::size_t k = 0; k < s.sectors.size(); ++k) {
    const Sector& x = s.sectors[k];
    // Visible vertices as coordinates: indices would need the vertex list to mean anything.
    nlohmann::json visible = nlohmann::json::array();
    for (int v : x.visible) visible.push_back({s.vertices[v].x(), s.vertices[v].y()});
    sectors.push_back(
        {{"id", k + 1},
         {"label", x.label},
         {"area_m2", x.area_m2},
         {"representative", {{"x", x.representative.x()}, {"y", x.representative.y()}}},
         {"ambiguous", x.ambiguous},
         {"n_min", x.n_min},
         {"n_min_two", x.n_min_two},
         {"visible_vertices", visible}});
  }
  return {{"polygons", a.polygons},
          {"cell_m", a.cell_m},
          {"sectors", sectors},
          {"sector_count", s.sectors.size()},
          {"ambiguous_count", ambiguous_count(s)},
          {"n_min_two", s.n_min_two()}};
}

/// Seed 000's Table 1 with the area, where the label was read, and the readings per turn.
void print_table(const SectorsArgs& a, const SectorMap& s) {
  std::size_t label_width = 5;
  for (const Sector& x : s.sectors) label_width = std::max(label_width, x.label.size());
  const int lw = static_cast<int>(label_width);
  std::printf("Visibility sectors of %s (%.3g m cells)\n", a.polygons.c_str(), a.cell_m);
  std::printf("%4s  %-*s  %8s  %-16s  %-9s  %7s  %9s\n", "Sec.", lw, "Label", "Area m2",
              "Representative", "Ambiguous", "n_min", "n_min_two");
  bool unreachable = false;
  for (std::size_t k = 0; k < s.sectors.size(); ++k) {
    const Sector& x = s.sectors[k];
    char where[48];
    std::snprintf(where, sizeof where, "(%.2f, %.2f)", x.representative.x(), x.representative.y());
    // 0 readings means no cell of the sector is clear of the walls: print "-", not 0.
    const std::string n_min = x.n_min > 0 ? std::to_string(x.n_min) : "-";
    const std::string n_min_two = x.n_min_two > 0 ? std::to_string(x.n_min_two) : "-";
    unreachable = unreachable || x.n_min == 0;
    std::printf("%4zu  %-*s  %8.2f  %-16s  %-9s  %7s  %9s\n", k + 1, lw,
                x.label.empty() ? "-" : x.label.c_str(), x.area_m2, where,
                x.ambiguous ? "yes" : "no", n_min.c_str(), n_min_two.c_str());
  }
  std::printf(
      "%zu sector%s, %d ambiguous (label equal to another's up to a turn, seed 000 4.1); "
      "N'_min %d readings per turn (seed 000 eq. 11)\n",
      s.sectors.size(), s.sectors.size() == 1 ? "" : "s", ambiguous_count(s), s.n_min_two());
  if (unreachable) {
    std::printf("n_min '-': no cell of the sector is %.2f m from the walls\n",
                SectorOptions{}.clearance_m);
  }
}

void run(const SectorsArgs& a) {
  if (!(a.cell_m > 0.0) || !std::isfinite(a.cell_m)) {
    throw Error("--cell must be a positive cell size in metres, got " + std::to_string(a.cell_m));
  }
  const PolygonMap map = load_polygon_map(a.polygons);
  // The folder first: a bad --out fails before the sectors are computed.
  if (!a.out.empty()) {
    std::error_code ec;
    fs::create_directories(a.out, ec);
    if (!fs::is_directory(a.out)) {
      throw Error("--out " + a.out + ": cannot create the folder" +
                  (ec ? " (" + ec.message() + ")" : ""));
    }
  }
  SectorOptions o;
  o.cell_m = a.cell_m;
  const SectorMap s = compute_sectors(map, o);
  const nlohmann::json j = sectors_json(a, s);

  std::string written;
  if (!a.out.empty()) {
    const fs::path dir(a.out);
    const std::string json_path = (dir / "sectors.json").string();
    const std::string png_path = (dir / "sectors.png").string();
    {
      std::ofstream f(json_path);
      f << j.dump(2) << "\n";
      if (!f) throw Error(json_path + ": cannot write the sectors");
    }
    plot::write_png(png_path, render_sectors(s, fs::path(a.polygons).filename().string()));
    written = "wrote " + png_path + " and " + json_path + "\n";
  }
  // stdout stays pure JSON with --json; the files are where --out said.
  if (a.json) {
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_table(a, s);
  std::cout << written;
}

}  // namespace

void add_sectors(CLI::App& app) {
  auto a = std::make_shared<SectorsArgs>();
  auto* cmd = app.add_subcommand(
      "sectors", "Visibility sectors of a polygon map and their labels (seed 000 Table 1)");
  cmd->add_option("--polygons", a->polygons, "polygon map (YAML with a 'boundary')")->required();
  cmd->add_option("--out", a->out, "folder for sectors.png and sectors.json (created if missing)");
  cmd->add_option("--cell", a->cell_m,
                  "sampling cell of the free space (m): smaller finds thinner sectors, slower")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print JSON instead of the table");
  cmd->callback([a] { run(*a); });
}

}  // namespace gridloc::cli
