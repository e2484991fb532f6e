// Visibility sectors as a JSON file: the polygon map, the options, the sampling grid (its
// cells' sectors run-length coded) and every sector.
#include "gridloc/engine/sectors/sector_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr const char* kFormat = "gridloc visibility sectors 1";

using nlohmann::json;

json points(const std::vector<Eigen::Vector2d>& ring) {
  json out = json::array();
  for (const Eigen::Vector2d& p : ring) out.push_back({p.x(), p.y()});
  return out;
}

std::vector<Eigen::Vector2d> read_points(const json& ring) {
  std::vector<Eigen::Vector2d> out;
  for (const json& p : ring) out.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  return out;
}

json map_json(const PolygonMap& map) {
  json obstacles = json::array();
  for (const Polygon& obstacle : map.obstacles) obstacles.push_back(points(obstacle));
  return {{"boundary", points(map.boundary)}, {"obstacles", obstacles}};
}

json options_json(const SectorOptions& options) {
  return {{"cell_m", options.cell_m},
          {"label_beams", options.label_beams},
          {"clearance_m", options.clearance_m}};
}

/// The cells' sectors as [value, count] runs.
json runs(const std::vector<int>& cells) {
  json out = json::array();
  for (std::size_t i = 0; i < cells.size();) {
    std::size_t j = i;
    while (j < cells.size() && cells[j] == cells[i]) ++j;
    out.push_back({cells[i], j - i});
    i = j;
  }
  return out;
}

json sector_json(const Sector& s) {
  return {
      {"label", s.label},         {"features", s.features},
      {"visible", s.visible},     {"representative", {s.representative.x(), s.representative.y()}},
      {"cells", s.cells},         {"area_m2", s.area_m2},
      {"ambiguous", s.ambiguous}, {"n_min", s.n_min},
      {"n_min_two", s.n_min_two}};
}

Sector read_sector(const json& j) {
  Sector s;
  s.label = j.at("label").get<std::string>();
  s.features = j.at("features").get<std::vector<int>>();
  s.visible = j.at("visible").get<std::vector<int>>();
  s.representative = {j.at("representative").at(0).get<double>(),
                      j.at("representative").at(1).get<double>()};
  s.cells = j.at("cells").get<int>();
  s.area_m2 = j.at("area_m2").get<double>();
  s.ambiguous = j.at("ambiguous").get<bool>();
  s.n_min = j.at("n_min").get<int>();
  s.n_min_two = j.at("n_min_two").get<int>();
  return s;
}

GridGeometry read_grid(const json& j) {
  GridGeometry grid;
  grid.resolution = j.at("resolution").get<double>();
  grid.origin = {j.at("origin").at(0).get<double>(), j.at("origin").at(1).get<double>()};
  grid.yaw = j.at("yaw").get<double>();
  grid.width = j.at("width").get<int>();
  grid.height = j.at("height").get<int>();
  return grid;
}

/// The runs expanded to one sector per cell; every value a sector index or -1.
std::vector<int> read_cells(const json& runs, std::size_t size, std::size_t sectors) {
  std::vector<int> cells;
  cells.reserve(size);
  for (const json& run : runs) {
    const int value = run.at(0).get<int>();
    const auto count = run.at(1).get<std::size_t>();
    if (value < -1 || value >= static_cast<int>(sectors) || count > size - cells.size()) {
      throw Error("a cell run names no sector or overruns the grid");
    }
    cells.insert(cells.end(), count, value);
  }
  if (cells.size() != size) throw Error("the cell runs do not cover the grid");
  return cells;
}

/// Throws unless the file's map and options are the ones asked for.
void check_match(const json& file, const PolygonMap& map, const SectorOptions& options) {
  if (file.at("map") != map_json(map)) {
    throw Error("the sectors were computed on another polygon map");
  }
  const json wanted = options_json(options);
  const json& saved = file.at("options");
  for (const char* key : {"cell_m", "label_beams", "clearance_m"}) {
    if (saved.at(key) != wanted.at(key)) {
      throw Error(std::string("the sectors were computed with ") + key + " " +
                  saved.at(key).dump() + ", not " + wanted.at(key).dump());
    }
  }
}

}  // namespace

void save_sectors(const SectorMap& sectors, const SectorOptions& options, const std::string& path) {
  json list = json::array();
  for (const Sector& s : sectors.sectors) list.push_back(sector_json(s));
  const GridGeometry& g = sectors.grid;
  const json file = {{"format", kFormat},
                     {"map", map_json(sectors.map)},
                     {"options", options_json(options)},
                     {"vertices", points(sectors.vertices)},
                     {"grid",
                      {{"resolution", g.resolution},
                       {"origin", {g.origin.x(), g.origin.y()}},
                       {"yaw", g.yaw},
                       {"width", g.width},
                       {"height", g.height}}},
                     {"cell_sectors", runs(sectors.sector_of)},
                     {"sectors", list}};
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write the sectors file");
  out << file.dump() << "\n";
  if (!out) throw Error(path + ": writing the sectors file failed");
}

SectorMap load_sectors(const std::string& path, const PolygonMap& map, const SectorOptions& options,
                       const ResourceLimits& limits) {
  const std::string text = read_input_file(path, "sectors file", limits);
  try {
    const json file = json::parse(text);
    if (file.at("format") != kFormat) throw Error("not a gridloc sectors file");
    check_match(file, map, options);
    SectorMap sectors;
    sectors.map = map;
    sectors.vertices = read_points(file.at("vertices"));
    for (const json& s : file.at("sectors")) sectors.sectors.push_back(read_sector(s));
    sectors.grid = read_grid(file.at("grid"));
    if (sectors.grid.width <= 0 || sectors.grid.height <= 0 ||
        static_cast<double>(sectors.grid.size()) > limits.max_cells) {
      throw Error("the sampling grid's size is not positive or over the cell limit");
    }
    sectors.sector_of =
        read_cells(file.at("cell_sectors"), sectors.grid.size(), sectors.sectors.size());
    for (const Sector& s : sectors.sectors) {
      if (s.features.size() != s.label.size()) {
        throw Error("a sector's features do not match its label");
      }
      for (int v : s.visible) {
        if (v < 0 || v >= static_cast<int>(sectors.vertices.size())) {
          throw Error("a sector sees a vertex the file does not list");
        }
      }
      for (int v : s.features) {
        if (v < -1 || v >= static_cast<int>(sectors.vertices.size())) {
          throw Error("a sector's feature names a vertex the file does not list");
        }
      }
    }
    return sectors;
  } catch (const json::exception& e) {
    throw Error(path + ": malformed sectors file (" + std::string(e.what()) + ")");
  } catch (const Error& e) {
    if (std::string(e.what()).rfind(path, 0) == 0) throw;
    throw Error(path + ": " + e.what());
  }
}

}  // namespace gridloc
