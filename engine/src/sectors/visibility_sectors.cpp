// Visibility sectors of a polygon map, sampled on a grid (see visibility_sectors.hpp).
#include "gridloc/engine/sectors/visibility_sectors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/sensors/segment_world.hpp"

namespace gridloc {
namespace {

/// The environment's vertices with, for each, its ring neighbours (free space on the left
/// of prev -> v -> next), and its edges as vertex index pairs.
struct Geometry {
  std::vector<Eigen::Vector2d> vertices;
  std::vector<int> prev, next;
  std::vector<std::pair<int, int>> edges;

  explicit Geometry(const PolygonMap& map) {
    const auto add = [&](const Polygon& ring) {
      const int base = static_cast<int>(vertices.size());
      const int n = static_cast<int>(ring.size());
      for (int i = 0; i < n; ++i) {
        vertices.push_back(ring[i]);
        prev.push_back(base + (i + n - 1) % n);
        next.push_back(base + (i + 1) % n);
        edges.emplace_back(base + i, base + (i + 1) % n);
      }
    };
    add(map.boundary);
    for (const auto& obstacle : map.obstacles) add(obstacle);
  }

  /// Vertex k is visible from p: the segment leaves k into free space (inside the wedge
  /// between its two edges) and properly crosses no edge.
  bool visible(const Eigen::Vector2d& p, int k) const {
    const Eigen::Vector2d d = p - vertices[k];
    if (d.squaredNorm() == 0.0) return true;
    const Eigen::Vector2d out = vertices[next[k]] - vertices[k],
                          in = vertices[prev[k]] - vertices[k];
    // Free space lies counter-clockwise from `out` to `in` around vertices[k].
    const auto ccw_angle = [](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
      double a = std::atan2(cross(from, to), from.dot(to));
      return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
    };
    const double a = ccw_angle(out, d);
    if (!(a > 0.0 && a < ccw_angle(out, in))) return false;
    for (const auto& [i, j] : edges) {
      if (i == k || j == k) continue;
      const Eigen::Vector2d &a0 = vertices[i], &a1 = vertices[j];
      const double o1 = cross(a1 - a0, p - a0), o2 = cross(a1 - a0, vertices[k] - a0);
      const double o3 = cross(vertices[k] - p, a0 - p), o4 = cross(vertices[k] - p, a1 - p);
      if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) &&
          ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
        return false;
      }
    }
    return true;
  }
};

bool in_free_space(const PolygonMap& map, const Eigen::Vector2d& p) {
  if (!inside(map.boundary, p)) return false;
  return std::none_of(map.obstacles.begin(), map.obstacles.end(),
                      [&](const Polygon& obstacle) { return inside(obstacle, p); });
}

/// The 4-neighbourhood's steps: east, west, north, south.
constexpr int kDx[4] = {1, -1, 0, 0}, kDy[4] = {0, 0, 1, -1};

/// The options' ranges; throws gridloc::Error naming the bad one.
void check_options(const SectorOptions& options) {
  options.limits.validate();
  if (!(options.cell_m > 0.0) || !std::isfinite(options.cell_m)) {
    throw Error("SectorOptions.cell_m must be positive, got " + std::to_string(options.cell_m));
  }
  if (!(options.clearance_m >= 0.0) || !std::isfinite(options.clearance_m)) {
    throw Error("SectorOptions.clearance_m must be >= 0, got " +
                std::to_string(options.clearance_m));
  }
  if (options.label_beams < 36) {
    throw Error("SectorOptions.label_beams must be >= 36, got " +
                std::to_string(options.label_beams));
  }
}

/// The boundary's bounding box: its lower and upper corners.
struct Box {
  Eigen::Vector2d lo, hi;
};

Box bounding_box(const Polygon& boundary) {
  Box box{boundary.front(), boundary.front()};
  for (const auto& p : boundary) box.lo = box.lo.cwiseMin(p), box.hi = box.hi.cwiseMax(p);
  return box;
}

/// Bytes per sampling cell besides its visible-vertex bits: the free flag, the face and sector
/// indices and the face's member list.
constexpr double kSectorBytesPerCell = 24.0;

/// The sampling grid over the bounding box, cells of `cell_m`; throws gridloc::Error when it
/// has more cells than limits.max_cells (checked as doubles, before the cast) or its visible
/// sets of `vertices` bits per cell would need more than limits.max_memory_mb.
GridGeometry sampling_grid(const Box& box, double cell_m, std::size_t vertices,
                           const ResourceLimits& limits) {
  const double width = std::ceil((box.hi.x() - box.lo.x()) / cell_m);
  const double height = std::ceil((box.hi.y() - box.lo.y()) / cell_m);
  const std::string what =
      "compute_sectors: the sampling grid of " + std::to_string(cell_m) +
      " m cells (a larger SectorOptions::cell_m, gridloc sectors --cell, makes it smaller)";
  const double cells = check_grid_cells(width, height, limits, what);
  const double words = std::ceil(static_cast<double>(vertices) / 64.0);
  check_memory(cells * (kSectorBytesPerCell + 8.0 * words), limits, what);
  GridGeometry grid;
  grid.resolution = cell_m;
  grid.origin = box.lo;
  grid.width = static_cast<int>(width);
  grid.height = static_cast<int>(height);
  return grid;
}

/// A grid cell's centre (world, m).
Eigen::Vector2d centre_of(const GridGeometry& grid, std::size_t cell) {
  const int ix = static_cast<int>(cell % grid.width), iy = static_cast<int>(cell / grid.width);
  return grid.origin + grid.cell_center(ix, iy);
}

/// Per grid cell: whether its centre lies in the free space, and the vertices visible from
/// there (one bit per vertex, `words` 64-bit words per cell).
struct Visibility {
  int words = 0;
  std::vector<char> free;
  std::vector<std::uint64_t> bits;

  /// Vertex k is visible from the cell's centre.
  bool sees(std::size_t cell, int k) const { return bits[cell * words + k / 64] >> (k % 64) & 1; }
  /// The two cells see the same vertices.
  bool same(std::size_t a, std::size_t b) const {
    return std::equal(bits.begin() + static_cast<std::ptrdiff_t>(a * words),
                      bits.begin() + static_cast<std::ptrdiff_t>((a + 1) * words),
                      bits.begin() + static_cast<std::ptrdiff_t>(b * words));
  }
};

/// The free cells and their visible-vertex sets (exact segment tests per cell centre).
Visibility visible_vertices(const PolygonMap& map, const Geometry& geometry,
                            const GridGeometry& grid) {
  const int nv = static_cast<int>(geometry.vertices.size());
  Visibility out;
  out.words = (nv + 63) / 64;
  const std::size_t cells = grid.size();
  out.free.assign(cells, 0);
  out.bits.assign(cells * static_cast<std::size_t>(out.words), 0);
#pragma omp parallel for schedule(dynamic, 4)
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      const Eigen::Vector2d p = grid.origin + grid.cell_center(ix, iy);
      if (!in_free_space(map, p)) continue;
      const std::size_t c = grid.index(ix, iy);
      out.free[c] = 1;
      for (int k = 0; k < nv; ++k) {
        if (geometry.visible(p, k))
          out.bits[c * out.words + k / 64] |= std::uint64_t{1} << (k % 64);
      }
    }
  }
  return out;
}

/// Faces: the 4-connected regions of free cells with one visible set.
struct Faces {
  std::vector<int> face;                          ///< per cell: its face, or -1
  std::vector<std::vector<std::size_t>> members;  ///< per face: its cells, in search order
};

/// The faces, found by breadth-first search from each unassigned free cell in index order.
Faces connected_faces(const GridGeometry& grid, const Visibility& visibility) {
  const std::size_t cells = grid.size();
  Faces out;
  out.face.assign(cells, -1);
  std::vector<int>& face = out.face;
  for (std::size_t s = 0; s < cells; ++s) {
    if (!visibility.free[s] || face[s] >= 0) continue;
    const int id = static_cast<int>(out.members.size());
    out.members.emplace_back();
    std::deque<std::size_t> queue{s};
    face[s] = id;
    while (!queue.empty()) {
      const std::size_t c = queue.front();
      queue.pop_front();
      out.members[id].push_back(c);
      const int cx = static_cast<int>(c % grid.width), cy = static_cast<int>(c / grid.width);
      for (int d = 0; d < 4; ++d) {
        const int nx = cx + kDx[d], ny = cy + kDy[d];
        if (!grid.contains(nx, ny)) continue;
        const std::size_t nc = grid.index(nx, ny);
        if (visibility.free[nc] && face[nc] < 0 && visibility.same(c, nc)) {
          face[nc] = id, queue.push_back(nc);
        }
      }
    }
  }
  return out;
}

/// A face's most interior cell (farthest, in 4-steps, from a cell of another face; the first
/// of the deepest in search order).
std::size_t most_interior_cell(const GridGeometry& grid, const Faces& faces, int id) {
  const std::vector<std::size_t>& members = faces.members[id];
  std::vector<int> depth(members.size(), -1);
  std::map<std::size_t, std::size_t> pos;
  for (std::size_t k = 0; k < members.size(); ++k) pos[members[k]] = k;
  std::deque<std::size_t> queue;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::size_t c = members[k];
    const int cx = static_cast<int>(c % grid.width), cy = static_cast<int>(c / grid.width);
    for (int d = 0; d < 4; ++d) {
      const int nx = cx + kDx[d], ny = cy + kDy[d];
      if (!grid.contains(nx, ny) || faces.face[grid.index(nx, ny)] != id) {
        depth[k] = 0;
        queue.push_back(k);
        break;
      }
    }
  }
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    const std::size_t c = members[k];
    const int cx = static_cast<int>(c % grid.width), cy = static_cast<int>(c / grid.width);
    for (int d = 0; d < 4; ++d) {
      const int nx = cx + kDx[d], ny = cy + kDy[d];
      if (!grid.contains(nx, ny)) continue;
      const auto it = pos.find(grid.index(nx, ny));
      if (it != pos.end() && depth[it->second] < 0) {
        depth[it->second] = depth[k] + 1;
        queue.push_back(it->second);
      }
    }
  }
  const std::size_t best =
      static_cast<std::size_t>(std::max_element(depth.begin(), depth.end()) - depth.begin());
  return members[best];
}

/// Per character of a label read by `scan` from `origin`: the visible vertex nearest the
/// reading of an M or D (within four beam steps and at least 5 cm), else -1.
std::vector<int> label_features(const Geometry& geometry, const std::vector<int>& visible,
                                const Eigen::Vector2d& origin, const RangeScan& scan,
                                const ScanLabel& label, int label_beams) {
  std::vector<int> features;
  for (std::size_t k = 0; k < label.label.size(); ++k) {
    int feature = -1;
    if (label.label[k] == 'M' || label.label[k] == 'D') {
      const int b = label.beam[k];
      const double r = scan.ranges[b];
      const Eigen::Vector2d hit =
          origin + r * Eigen::Vector2d(std::cos(scan.angles[b]), std::sin(scan.angles[b]));
      double best = std::max(0.05, 4.0 * r * 2.0 * std::numbers::pi / label_beams);
      for (int v : visible) {
        const double d = (geometry.vertices[v] - hit).norm();
        if (d < best) best = d, feature = v;
      }
    }
    features.push_back(feature);
  }
  return features;
}

/// One sector per face: its most interior cell, cells and visible set, and the label (with
/// its features) of a dense noise-free scan from there, heading 0, of range `reach`.
std::vector<Sector> face_sectors(const PolygonMap& map, const Geometry& geometry,
                                 const GridGeometry& grid, const Visibility& visibility,
                                 const Faces& faces, double reach, const SectorOptions& options) {
  ScanLabelOptions dense = options.label;
  dense.median_window = 1;
  const int nv = static_cast<int>(geometry.vertices.size());
  const int nf = static_cast<int>(faces.members.size());
  std::vector<Sector> out(static_cast<std::size_t>(nf));
  for (int id = 0; id < nf; ++id) {
    Sector& s = out[id];
    s.representative = centre_of(grid, most_interior_cell(grid, faces, id));
    s.cells = static_cast<int>(faces.members[id].size());
    const std::size_t c0 = faces.members[id].front();
    for (int k = 0; k < nv; ++k) {
      if (visibility.sees(c0, k)) s.visible.push_back(k);
    }
    const RangeScan scan = polygon_scan(map, {s.representative.x(), s.representative.y(), 0.0},
                                        options.label_beams, reach);
    const ScanLabel label = construct_scan_label(scan, dense);
    s.label = label.label;
    s.features =
        label_features(geometry, s.visible, s.representative, scan, label, options.label_beams);
  }
  return out;
}

/// Union-find over faces, with path halving.
struct FaceGroups {
  std::vector<int> parent;
  explicit FaceGroups(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
};

/// Seed 000's merge: adjacent faces with one label are one sector. The largest face of each
/// merged group speaks for it (representative, visible set, features); the cells add up.
/// Fills out.sectors (in order of each group's first face), out.sector_of and the areas.
void merge_equal_labels(const GridGeometry& grid, const Faces& faces,
                        const std::vector<Sector>& face_sector, double cell_m, SectorMap& out) {
  const std::vector<int>& face = faces.face;
  const std::size_t cells = grid.size();
  const int nf = static_cast<int>(face_sector.size());
  FaceGroups groups(nf);
  for (std::size_t c = 0; c < cells; ++c) {
    if (face[c] < 0) continue;
    const int cx = static_cast<int>(c % grid.width), cy = static_cast<int>(c / grid.width);
    for (int d = 0; d < 2; ++d) {  // east and north neighbours
      const int nx = cx + (d == 0), ny = cy + (d == 1);
      if (!grid.contains(nx, ny)) continue;
      const int f = face[grid.index(nx, ny)];
      if (f >= 0 && f != face[c] && face_sector[f].label == face_sector[face[c]].label) {
        groups.parent[groups.find(f)] = groups.find(face[c]);
      }
    }
  }
  std::vector<int> largest(static_cast<std::size_t>(nf), -1),
      total(static_cast<std::size_t>(nf), 0);
  for (int id = 0; id < nf; ++id) {
    const int root = groups.find(id);
    if (largest[root] < 0 || face_sector[id].cells > face_sector[largest[root]].cells) {
      largest[root] = id;
    }
    total[root] += face_sector[id].cells;
  }
  std::vector<int> sector_of_face(static_cast<std::size_t>(nf), -1);
  for (int id = 0; id < nf; ++id) {
    const int root = groups.find(id);
    if (sector_of_face[root] < 0) {
      sector_of_face[root] = static_cast<int>(out.sectors.size());
      out.sectors.push_back(face_sector[largest[root]]);
      out.sectors.back().cells = total[root];
    }
    sector_of_face[id] = sector_of_face[root];
  }
  out.sector_of.assign(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    if (face[c] >= 0) out.sector_of[c] = sector_of_face[face[c]];
  }
  for (auto& s : out.sectors) s.area_m2 = s.cells * cell_m * cell_m;
}

/// Seed 000 §4.1: labels one turn away from another sector's are ambiguous.
void mark_turned_twins(std::vector<Sector>& sectors) {
  for (std::size_t a = 0; a < sectors.size(); ++a) {
    for (std::size_t b = a + 1; b < sectors.size(); ++b) {
      if (cyclic_equal(sectors[a].label, sectors[b].label)) {
        sectors[a].ambiguous = sectors[b].ambiguous = true;
      }
    }
  }
}

/// The distance from `p` to the nearest edge (m).
double wall_distance(const Geometry& geometry, const Eigen::Vector2d& p) {
  return distance_to_nearest(p, geometry.edges.size(), [&](std::size_t k) {
    const auto [i, j] = geometry.edges[k];
    return Segment2{geometry.vertices[i], geometry.vertices[j]};
  });
}

/// Seed 000 eq. (10)-(11): alpha = the smallest angle a fully visible edge subtends over a
/// sector's cells at least clearance_m from the walls; n_min = 6 pi / alpha, n_min_two =
/// 4 pi / alpha.
void set_minimum_readings(const Geometry& geometry, const Visibility& visibility,
                          double clearance_m, SectorMap& out) {
  const GridGeometry& grid = out.grid;
  std::vector<double> alpha(out.sectors.size(), std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < grid.size(); ++c) {
    const int s = out.sector_of[c];
    if (s < 0) continue;
    const Eigen::Vector2d p = centre_of(grid, c);
    // Where the robot cannot stand (nearer a wall than the clearance) does not count: at a
    // wall, the wall itself subtends no angle and N_min has no bound (seed 000 §4.2).
    if (wall_distance(geometry, p) < clearance_m) continue;
    for (const auto& [i, j] : geometry.edges) {
      if (!visibility.sees(c, i) || !visibility.sees(c, j)) continue;
      const Eigen::Vector2d a = geometry.vertices[i] - p, b = geometry.vertices[j] - p;
      alpha[s] = std::min(alpha[s], std::abs(std::atan2(cross(a, b), a.dot(b))));
    }
  }
  for (std::size_t s = 0; s < out.sectors.size(); ++s) {
    if (!std::isfinite(alpha[s]) || alpha[s] <= 0.0) continue;
    out.sectors[s].n_min = static_cast<int>(std::ceil(6.0 * std::numbers::pi / alpha[s]));
    out.sectors[s].n_min_two = static_cast<int>(std::ceil(4.0 * std::numbers::pi / alpha[s]));
  }
}

}  // namespace

RangeScan polygon_scan(const PolygonMap& map, const Pose2& pose, int beams, double max_range) {
  std::vector<WallSegment> walls;
  for (const auto& [a, b] : polygon_edges(map)) walls.push_back({a, b});
  return simulate_segment_scan(walls, pose, beams, 0.0, 2.0 * std::numbers::pi / beams, max_range);
}

int SectorMap::sector_at(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d g = p - grid.origin;
  const Cell c = grid.cell_of(g.x(), g.y());
  if (!grid.contains(c.ix, c.iy)) return -1;
  return sector_of[grid.index(c.ix, c.iy)];
}

int SectorMap::n_min_two() const {
  int n = 0;
  for (const auto& s : sectors) n = std::max(n, s.n_min_two);
  return n;
}

SectorMap compute_sectors(const PolygonMap& map, const SectorOptions& options) {
  check_options(options);
  SectorMap out;
  out.map = map;
  const Geometry geometry(map);
  out.vertices = geometry.vertices;
  const Box box = bounding_box(map.boundary);
  out.grid = sampling_grid(box, options.cell_m, geometry.vertices.size(), options.limits);
  const Visibility visibility = visible_vertices(map, geometry, out.grid);
  const Faces faces = connected_faces(out.grid, visibility);
  const double reach = 2.0 * (box.hi - box.lo).norm() + 1.0;
  const std::vector<Sector> face_sector =
      face_sectors(map, geometry, out.grid, visibility, faces, reach, options);
  merge_equal_labels(out.grid, faces, face_sector, options.cell_m, out);
  mark_turned_twins(out.sectors);
  set_minimum_readings(geometry, visibility, options.clearance_m, out);
  return out;
}

}  // namespace gridloc
