#include "gridloc/grids/polygon_map.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc {
namespace {

/// Bytes of a polygon map file allowed per vertex of limits.max_vertices (a vertex written
/// with 17 digits and comments takes well under this).
constexpr double kYamlBytesPerVertex = 256.0;

/// Orientation of c relative to the line a -> b: > 0 left, < 0 right, 0 on it.
double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

/// c lies on segment [a, b], given that the three are collinear.
bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

/// Segments [a, b] and [c, d] share at least one point (crossing or touching).
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d);
  const double o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    return true;
  }
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

std::string point_text(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

/// The first repeated vertex of ring[0, count): (j, i) with j < i, i the smallest index that
/// repeats an earlier vertex and j the first vertex it repeats; none when i == 0. Sorting
/// makes it O(n log n) (the vertices must be finite).
std::pair<std::size_t, std::size_t> first_repeat(const Polygon& ring, std::size_t count) {
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) {
    const Eigen::Vector2d &u = ring[p], &v = ring[q];
    return u.x() != v.x() ? u.x() < v.x() : u.y() != v.y() ? u.y() < v.y() : p < q;
  });
  std::pair<std::size_t, std::size_t> first{0, 0};
  for (std::size_t k = 1; k < order.size(); ++k) {
    // Within a group of equal vertices sorted by index, the first two are its earliest repeat.
    const bool starts_repeat =
        ring[order[k]] == ring[order[k - 1]] && (k < 2 || ring[order[k - 1]] != ring[order[k - 2]]);
    if (starts_repeat && (first.second == 0 || order[k] < first.second)) {
      first = {order[k - 1], order[k]};
    }
  }
  return first;
}

/// Vertices: finite and none repeated, reported in the order a vertex-by-vertex scan meets them.
void check_vertices(const Polygon& ring, const std::string& name) {
  std::size_t finite = 0;
  while (finite < ring.size() && ring[finite].allFinite()) ++finite;
  const auto [j, i] = first_repeat(ring, finite);
  if (i > 0) {
    throw Error(name + " repeats vertex " + point_text(ring[i]) + " (vertices " +
                std::to_string(j) + " and " + std::to_string(i) +
                "); only the closing vertex may repeat the first");
  }
  if (finite < ring.size()) {
    throw Error(name + " vertex " + std::to_string(finite) + " is not finite");
  }
}

/// The first pair of non-adjacent edges (i, j), i < j, that meet, in lexicographic order;
/// (n, n) when none do. A sweep over the edges sorted by their smallest x compares only edges
/// whose boxes overlap (O(n log n) for the usual maps, quadratic only for edges stacked in x).
std::pair<std::size_t, std::size_t> first_crossing(const Polygon& ring) {
  const std::size_t n = ring.size();
  const auto lo_x = [&](std::size_t e) { return std::min(ring[e].x(), ring[(e + 1) % n].x()); };
  const auto hi_x = [&](std::size_t e) { return std::max(ring[e].x(), ring[(e + 1) % n].x()); };
  const auto lo_y = [&](std::size_t e) { return std::min(ring[e].y(), ring[(e + 1) % n].y()); };
  const auto hi_y = [&](std::size_t e) { return std::max(ring[e].y(), ring[(e + 1) % n].y()); };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) {
    return lo_x(p) != lo_x(q) ? lo_x(p) < lo_x(q) : p < q;
  });
  std::pair<std::size_t, std::size_t> first{n, n};
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t q = p + 1; q < n && lo_x(order[q]) <= hi_x(order[p]); ++q) {
      const std::size_t i = std::min(order[p], order[q]), j = std::max(order[p], order[q]);
      if (j < i + 2 || (i == 0 && j == n - 1)) continue;  // adjacent edges share a vertex
      if (lo_y(i) > hi_y(j) || lo_y(j) > hi_y(i) || std::pair{i, j} >= first) continue;
      if (segments_meet(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) first = {i, j};
    }
  }
  return first;
}

/// The checks of one ring on its own.
void check_ring(const Polygon& ring, const std::string& name) {
  if (ring.size() < 3) {
    throw Error(name + " has " + std::to_string(ring.size()) + " vertices, needs at least 3");
  }
  check_vertices(ring, name);
  const std::size_t n = ring.size();
  const auto [i, j] = first_crossing(ring);
  // An edge folding back onto the next one, met by an edge-by-edge scan before edge i's
  // crossings.
  for (std::size_t k = 0; k < n && k <= i; ++k) {
    const Eigen::Vector2d &a = ring[k], &b = ring[(k + 1) % n], &c = ring[(k + 2) % n];
    if (orient(a, b, c) == 0.0 && (b - a).dot(c - b) < 0.0) {
      throw Error(name + " is not simple: it folds back at vertex " + point_text(b));
    }
  }
  if (i < n) {
    throw Error(name + " is not simple: edges " + std::to_string(i) + " " + point_text(ring[i]) +
                "-" + point_text(ring[(i + 1) % n]) + " and " + std::to_string(j) + " " +
                point_text(ring[j]) + "-" + point_text(ring[(j + 1) % n]) + " cross");
  }
  if (signed_area2(ring) == 0.0) throw Error(name + " has zero area");
}

bool rings_meet(const Polygon& p, const Polygon& q) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < q.size(); ++j) {
      if (segments_meet(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return true;
    }
  }
  return false;
}

Eigen::Vector2d read_vertex(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence() || node.size() != 2) {
    throw Error(where + ": a vertex must be [x, y]");
  }
  try {
    return {node[0].as<double>(), node[1].as<double>()};
  } catch (const YAML::Exception&) {
    throw Error(where + ": a vertex must be two numbers [x, y]");
  }
}

Polygon read_ring(const YAML::Node& node, const std::string& where) {
  if (!node.IsSequence()) throw Error(where + " must be a list of [x, y] vertices");
  Polygon ring;
  for (std::size_t i = 0; i < node.size(); ++i) {
    ring.push_back(read_vertex(node[i], where + " vertex " + std::to_string(i)));
  }
  if (ring.size() < 2 || ring.front() != ring.back()) {
    throw Error(where + " is not closed: its last vertex must repeat the first " +
                (ring.empty() ? std::string("(it is empty)") : point_text(ring.front())));
  }
  ring.pop_back();
  return ring;
}

/// The number of vertices and the coordinates of every ring within the limits, before the
/// (quadratic) checks of make_polygon_map run.
void check_polygon_limits(const Polygon& boundary, const std::vector<Polygon>& obstacles,
                          const ResourceLimits& limits) {
  double vertices = static_cast<double>(boundary.size());
  for (const auto& o : obstacles) vertices += static_cast<double>(o.size());
  check_limit(vertices, limits.max_vertices, "the polygon map's rings", "vertices",
              LimitNames::vertices);
  const auto check_ring_coordinates = [&](const Polygon& ring, const std::string& name) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      if (!ring[i].allFinite()) continue;  // check_ring names it
      check_limit(ring[i].cwiseAbs().maxCoeff(), limits.max_coordinate_m,
                  name + " vertex " + std::to_string(i) + ": a coordinate", "m",
                  LimitNames::coordinate_m);
    }
  };
  check_ring_coordinates(boundary, "boundary");
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    check_ring_coordinates(obstacles[k], "obstacle " + std::to_string(k));
  }
}

/// The rings of a polygon map file, their vertex count checked against the limit as they are
/// read (before they are stored).
struct FileRings {
  Polygon boundary;
  std::vector<Polygon> obstacles;
};

FileRings read_rings(const YAML::Node& root, const ResourceLimits& limits) {
  const YAML::Node obstacle_nodes = root["obstacles"];
  if (obstacle_nodes && !obstacle_nodes.IsSequence()) {
    throw Error("obstacles must be a list of rings");
  }
  // Each ring of the file repeats its first vertex at the end; that one is not counted.
  const auto ring_vertices = [](const YAML::Node& ring) {
    return ring.IsSequence() && ring.size() > 0 ? ring.size() - 1.0 : 0.0;
  };
  double vertices = ring_vertices(root["boundary"]);
  for (std::size_t k = 0; obstacle_nodes && k < obstacle_nodes.size(); ++k) {
    vertices += ring_vertices(obstacle_nodes[k]);
  }
  check_limit(vertices, limits.max_vertices, "its rings", "vertices", LimitNames::vertices);
  FileRings rings{read_ring(root["boundary"], "boundary"), {}};
  for (std::size_t k = 0; obstacle_nodes && k < obstacle_nodes.size(); ++k) {
    rings.obstacles.push_back(read_ring(obstacle_nodes[k], "obstacle " + std::to_string(k)));
  }
  return rings;
}

/// The x of every crossing of the rings' edges with the line at height y, in increasing order:
/// the crossings inside() counts, computed by the same expression.
std::vector<double> row_crossings(const std::vector<const Polygon*>& rings, double y) {
  std::vector<double> xs;
  for (const Polygon* ring : rings) {
    const std::size_t n = ring->size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Eigen::Vector2d &a = (*ring)[i], &b = (*ring)[j];
      if ((a.y() > y) != (b.y() > y)) {
        xs.push_back((b.x() - a.x()) * (y - a.y()) / (b.y() - a.y()) + a.x());
      }
    }
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

/// Walks a row's cell centres left to right, saying whether each lies inside the rings whose
/// crossings it holds (an odd number of crossings to its right: the even-odd rule).
class RowParity {
 public:
  explicit RowParity(std::vector<double> crossings) : xs_(std::move(crossings)) {}
  bool inside(double x) {
    while (next_ < xs_.size() && xs_[next_] <= x) ++next_;
    return (xs_.size() - next_) % 2 == 1;
  }

 private:
  std::vector<double> xs_;
  std::size_t next_ = 0;
};

/// Row iy of the rasterized map: Free inside the boundary, Occupied inside an obstacle (the
/// obstacles are disjoint, so the parity of all their crossings is "inside one of them"). A
/// centre exactly on an edge may differ from inside()'s answer, but such a cell is a wall cell
/// and the walls are drawn over the rows.
void fill_row(OccupancyMap& out, const PolygonMap& map, int iy) {
  const GridGeometry& g = out.geometry;
  const double y = (g.origin + g.cell_center(0, iy)).y();
  std::vector<const Polygon*> obstacles;
  for (const auto& o : map.obstacles) obstacles.push_back(&o);
  RowParity in_boundary(row_crossings({&map.boundary}, y));
  RowParity in_obstacle(row_crossings(obstacles, y));
  for (int ix = 0; ix < g.width; ++ix) {
    const Eigen::Vector2d c = g.origin + g.cell_center(ix, iy);
    const bool free_side = in_boundary.inside(c.x());
    const bool obstacle = in_obstacle.inside(c.x());
    if (free_side) out.at(ix, iy) = obstacle ? CellState::Occupied : CellState::Free;
  }
}

}  // namespace

double signed_area2(const Polygon& polygon) {
  double a = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    a += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return a;
}

bool inside(const Polygon& polygon, const Eigen::Vector2d& p) {
  bool in = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d &a = polygon[i], &b = polygon[j];
    if (orient(a, b, p) == 0.0 && on_segment(a, b, p)) return false;  // on an edge
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

PolygonMap make_polygon_map(Polygon boundary, std::vector<Polygon> obstacles, double resolution,
                            const ResourceLimits& limits) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("polygon map: resolution must be positive, got " + std::to_string(resolution));
  }
  check_polygon_limits(boundary, obstacles, limits);
  check_ring(boundary, "boundary");
  if (signed_area2(boundary) < 0.0) std::reverse(boundary.begin(), boundary.end());
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const std::string name = "obstacle " + std::to_string(k);
    Polygon& o = obstacles[k];
    check_ring(o, name);
    if (signed_area2(o) > 0.0) std::reverse(o.begin(), o.end());
    for (const auto& v : o) {
      if (!inside(boundary, v)) {
        throw Error(name + " vertex " + point_text(v) + " is not strictly inside the boundary");
      }
    }
    if (rings_meet(o, boundary)) throw Error(name + " touches the boundary");
    for (std::size_t j = 0; j < k; ++j) {
      if (rings_meet(o, obstacles[j]) || inside(obstacles[j], o.front()) ||
          inside(o, obstacles[j].front())) {
        throw Error(name + " touches or overlaps obstacle " + std::to_string(j) +
                    ": join them into one polygon");
      }
    }
  }
  return {std::move(boundary), std::move(obstacles), resolution};
}

bool is_polygon_map_file(const std::string& path, const ResourceLimits& limits) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".yaml" && ext != ".yml") return false;
  try {
    // Only a polygon map can be larger than any map_server YAML: its loader checks the size.
    if (check_input_file(path, "map YAML", limits) > kMaxMapYamlBytes) return true;
    const YAML::Node root = YAML::Load(read_input_file(path, "map YAML", limits));
    return root.IsMap() && root["boundary"];
  } catch (const YAML::Exception&) {
    return false;
  } catch (const Error&) {
    return false;  // not a readable file: the map loader that follows says why
  }
}

PolygonMap load_polygon_map(const std::string& path, const ResourceLimits& limits) {
  // YAML parsing takes about 65 bytes of memory per byte of the file: the file is bounded by
  // what the vertex limit allows before it is parsed.
  const double bytes = static_cast<double>(check_input_file(path, "polygon map", limits));
  check_limit(bytes, kYamlBytesPerVertex * limits.max_vertices + kMaxMapYamlBytes,
              "polygon map " + path + " (" + std::to_string(int(kYamlBytesPerVertex)) +
                  " bytes of YAML per vertex allowed)",
              "bytes", LimitNames::vertices);
  const std::string text = read_input_file(path, "polygon map", limits);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error("polygon map " + path + ": not valid YAML: " + e.what());
  }
  if (!root.IsMap() || !root["boundary"]) {
    throw Error("polygon map " + path + ": no 'boundary' key (is it a map_server map?)");
  }
  try {
    double resolution = 0.05;
    if (root["resolution"]) {
      try {
        resolution = root["resolution"].as<double>();
      } catch (const YAML::Exception&) {
        throw Error("resolution must be a number");
      }
    }
    FileRings rings = read_rings(root, limits);
    return make_polygon_map(std::move(rings.boundary), std::move(rings.obstacles), resolution,
                            limits);
  } catch (const Error& e) {
    throw Error("polygon map " + path + ": " + e.what());
  }
}

namespace {

/// The shortest text that reads back as exactly `value` (std::to_chars' round-trip form).
std::string number_text(double value) {
  std::array<char, 32> text{};
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc{} ? std::string(text.data(), end) : std::string("nan");
}

/// A ring as the file format writes it: `[[x, y], ...]`, closed by repeating its first vertex.
void write_ring(std::ostream& out, const Polygon& ring) {
  out << "[";
  for (std::size_t i = 0; i <= ring.size(); ++i) {
    const Eigen::Vector2d& v = ring[i % ring.size()];
    out << (i > 0 ? ", [" : "[") << number_text(v.x()) << ", " << number_text(v.y()) << "]";
  }
  out << "]";
}

}  // namespace

void save_polygon_map(const PolygonMap& map, const std::string& path, const std::string& comment) {
  if (map.boundary.empty()) throw Error("polygon map " + path + ": the boundary is empty");
  for (std::size_t k = 0; k < map.obstacles.size(); ++k) {
    if (map.obstacles[k].empty()) {
      throw Error("polygon map " + path + ": obstacle " + std::to_string(k) + " is empty");
    }
  }
  std::ofstream out(path);
  if (!out) throw Error("polygon map " + path + ": cannot open the file for writing");
  out << "# gridloc polygon map (format: grids/include/gridloc/grids/polygon_map.hpp)\n";
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << "resolution: " << number_text(map.resolution) << "\nboundary: ";
  write_ring(out, map.boundary);
  out << "\n";
  if (!map.obstacles.empty()) out << "obstacles:\n";
  for (const Polygon& obstacle : map.obstacles) {
    out << "  - ";
    write_ring(out, obstacle);
    out << "\n";
  }
  out.flush();
  if (!out) throw Error("polygon map " + path + ": cannot write the file");
}

std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> polygon_edges(const PolygonMap& map) {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> edges;
  const auto add = [&](const Polygon& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      edges.emplace_back(ring[i], ring[(i + 1) % ring.size()]);
    }
  };
  add(map.boundary);
  for (const auto& o : map.obstacles) add(o);
  return edges;
}

OccupancyMap rasterize_polygon_map(const PolygonMap& map, double resolution, double margin_m,
                                   const ResourceLimits& limits) {
  if (resolution == 0.0) resolution = map.resolution;
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("rasterize_polygon_map: resolution must be positive, got " +
                std::to_string(resolution));
  }
  if (!(margin_m >= 0.0) || !std::isfinite(margin_m)) {
    throw Error("rasterize_polygon_map: margin must be >= 0, got " + std::to_string(margin_m));
  }
  Eigen::Vector2d lo = map.boundary.front(), hi = lo;
  for (const auto& v : map.boundary) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  GridGeometry g;
  g.resolution = resolution;
  g.origin = lo - Eigen::Vector2d::Constant(margin_m);
  const double width = std::ceil((hi.x() - lo.x() + 2 * margin_m) / resolution);
  const double height = std::ceil((hi.y() - lo.y() + 2 * margin_m) / resolution);
  check_grid_cells(width, height, limits,
                   "the polygon map rasterized at " + std::to_string(resolution) + " m");
  g.width = static_cast<int>(width);
  g.height = static_cast<int>(height);
  OccupancyMap out(g, CellState::Unknown);
  for (int iy = 0; iy < g.height; ++iy) fill_row(out, map, iy);
  // Walls: every cell an edge passes through, sampled finer than a cell so none is skipped.
  for (const auto& [a, b] : polygon_edges(map)) {
    const int steps = static_cast<int>(std::ceil((b - a).norm() / (0.125 * resolution))) + 1;
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(k) / steps) - g.origin;
      const Cell cell = g.cell_of(p.x(), p.y());
      if (g.contains(cell.ix, cell.iy)) out.at(cell.ix, cell.iy) = CellState::Occupied;
    }
  }
  return out;
}

}  // namespace gridloc
