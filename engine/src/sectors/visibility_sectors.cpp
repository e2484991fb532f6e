// Visibility sectors of a polygon map, sampled on a grid (see visibility_sectors.hpp).
#include "gridloc/engine/sectors/visibility_sectors.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/segment_world.hpp"

namespace gridloc {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The environment's vertices with, for each, its ring neighbours (free space on the left
/// of prev -> v -> next), and its edges as vertex index pairs.
struct Geometry {
  std::vector<Eigen::Vector2d> v;
  std::vector<int> prev, next;
  std::vector<std::pair<int, int>> edges;

  explicit Geometry(const PolygonMap& map) {
    const auto add = [&](const Polygon& ring) {
      const int base = static_cast<int>(v.size());
      const int n = static_cast<int>(ring.size());
      for (int i = 0; i < n; ++i) {
        v.push_back(ring[i]);
        prev.push_back(base + (i + n - 1) % n);
        next.push_back(base + (i + 1) % n);
        edges.emplace_back(base + i, base + (i + 1) % n);
      }
    };
    add(map.boundary);
    for (const auto& o : map.obstacles) add(o);
  }

  /// Vertex k is visible from p: the segment leaves k into free space (inside the wedge
  /// between its two edges) and properly crosses no edge.
  bool visible(const Eigen::Vector2d& p, int k) const {
    const Eigen::Vector2d d = p - v[k];
    if (d.squaredNorm() == 0.0) return true;
    const Eigen::Vector2d out = v[next[k]] - v[k], in = v[prev[k]] - v[k];
    // Free space lies counter-clockwise from `out` to `in` around v[k].
    const auto ccw_angle = [](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
      double a = std::atan2(cross(from, to), from.dot(to));
      return a < 0.0 ? a + 2.0 * std::numbers::pi : a;
    };
    const double a = ccw_angle(out, d);
    if (!(a > 0.0 && a < ccw_angle(out, in))) return false;
    for (const auto& [i, j] : edges) {
      if (i == k || j == k) continue;
      const Eigen::Vector2d &a0 = v[i], &a1 = v[j];
      const double o1 = cross(a1 - a0, p - a0), o2 = cross(a1 - a0, v[k] - a0);
      const double o3 = cross(v[k] - p, a0 - p), o4 = cross(v[k] - p, a1 - p);
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
                      [&](const Polygon& o) { return inside(o, p); });
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

SectorMap compute_sectors(const PolygonMap& map, const SectorOptions& o) {
  if (!(o.cell_m > 0.0) || !std::isfinite(o.cell_m)) {
    throw Error("SectorOptions.cell_m must be positive, got " + std::to_string(o.cell_m));
  }
  if (!(o.clearance_m >= 0.0) || !std::isfinite(o.clearance_m)) {
    throw Error("SectorOptions.clearance_m must be >= 0, got " + std::to_string(o.clearance_m));
  }
  if (o.label_beams < 36) {
    throw Error("SectorOptions.label_beams must be >= 36, got " + std::to_string(o.label_beams));
  }
  SectorMap out;
  out.map = map;
  const Geometry geo(map);
  out.vertices = geo.v;
  const int nv = static_cast<int>(geo.v.size());
  const int words = (nv + 63) / 64;

  Eigen::Vector2d lo = map.boundary.front(), hi = lo;
  for (const auto& p : map.boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  GridGeometry& g = out.grid;
  g.resolution = o.cell_m;
  g.origin = lo;
  g.width = static_cast<int>(std::ceil((hi.x() - lo.x()) / o.cell_m));
  g.height = static_cast<int>(std::ceil((hi.y() - lo.y()) / o.cell_m));
  if (static_cast<double>(g.width) * g.height > 2e7) {
    throw Error(
        "compute_sectors: " + std::to_string(g.width) + " x " + std::to_string(g.height) +
        " cells; use a larger sampling cell (SectorOptions::cell_m, gridloc sectors --cell)");
  }
  const std::size_t cells = g.size();
  std::vector<char> free(cells, 0);
  std::vector<std::uint64_t> bits(cells * static_cast<std::size_t>(words), 0);
  const auto centre = [&](int ix, int iy) -> Eigen::Vector2d {
    return g.origin + g.cell_center(ix, iy);
  };
#pragma omp parallel for schedule(dynamic, 4)
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d p = centre(ix, iy);
      if (!in_free_space(map, p)) continue;
      const std::size_t c = g.index(ix, iy);
      free[c] = 1;
      for (int k = 0; k < nv; ++k) {
        if (geo.visible(p, k)) bits[c * words + k / 64] |= std::uint64_t{1} << (k % 64);
      }
    }
  }
  const auto same = [&](std::size_t a, std::size_t b) {
    return std::equal(bits.begin() + static_cast<std::ptrdiff_t>(a * words),
                      bits.begin() + static_cast<std::ptrdiff_t>((a + 1) * words),
                      bits.begin() + static_cast<std::ptrdiff_t>(b * words));
  };

  // Faces: 4-connected cells with one visible set.
  std::vector<int> face(cells, -1);
  std::vector<std::vector<std::size_t>> members;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (std::size_t s = 0; s < cells; ++s) {
    if (!free[s] || face[s] >= 0) continue;
    const int id = static_cast<int>(members.size());
    members.emplace_back();
    std::deque<std::size_t> q{s};
    face[s] = id;
    while (!q.empty()) {
      const std::size_t c = q.front();
      q.pop_front();
      members[id].push_back(c);
      const int cx = static_cast<int>(c % g.width), cy = static_cast<int>(c / g.width);
      for (int d = 0; d < 4; ++d) {
        const int nx = cx + dx[d], ny = cy + dy[d];
        if (!g.contains(nx, ny)) continue;
        const std::size_t nc = g.index(nx, ny);
        if (free[nc] && face[nc] < 0 && same(c, nc)) face[nc] = id, q.push_back(nc);
      }
    }
  }

  // Each face's most interior cell (farthest, in 4-steps, from a cell of another face).
  const auto representative = [&](int id) {
    std::vector<int> depth(members[id].size(), -1);
    std::map<std::size_t, std::size_t> pos;
    for (std::size_t k = 0; k < members[id].size(); ++k) pos[members[id][k]] = k;
    std::deque<std::size_t> q;
    for (std::size_t k = 0; k < members[id].size(); ++k) {
      const std::size_t c = members[id][k];
      const int cx = static_cast<int>(c % g.width), cy = static_cast<int>(c / g.width);
      for (int d = 0; d < 4; ++d) {
        const int nx = cx + dx[d], ny = cy + dy[d];
        if (!g.contains(nx, ny) || face[g.index(nx, ny)] != id) {
          depth[k] = 0;
          q.push_back(k);
          break;
        }
      }
    }
    while (!q.empty()) {
      const std::size_t k = q.front();
      q.pop_front();
      const std::size_t c = members[id][k];
      const int cx = static_cast<int>(c % g.width), cy = static_cast<int>(c / g.width);
      for (int d = 0; d < 4; ++d) {
        const int nx = cx + dx[d], ny = cy + dy[d];
        if (!g.contains(nx, ny)) continue;
        const auto it = pos.find(g.index(nx, ny));
        if (it != pos.end() && depth[it->second] < 0) {
          depth[it->second] = depth[k] + 1;
          q.push_back(it->second);
        }
      }
    }
    const std::size_t best =
        static_cast<std::size_t>(std::max_element(depth.begin(), depth.end()) - depth.begin());
    const std::size_t c = members[id][best];
    return centre(static_cast<int>(c % g.width), static_cast<int>(c / g.width));
  };

  // Labels from a dense noise-free scan at each face's representative point, heading 0.
  const double reach = 2.0 * (hi - lo).norm() + 1.0;
  ScanLabelOptions dense = o.label;
  dense.median_window = 1;
  const int nf = static_cast<int>(members.size());
  std::vector<Sector> faces(static_cast<std::size_t>(nf));
  for (int id = 0; id < nf; ++id) {
    Sector& s = faces[id];
    s.representative = representative(id);
    s.cells = static_cast<int>(members[id].size());
    const std::size_t c0 = members[id].front();
    for (int k = 0; k < nv; ++k) {
      if (bits[c0 * words + k / 64] >> (k % 64) & 1) s.visible.push_back(k);
    }
    const RangeScan scan =
        polygon_scan(map, {s.representative.x(), s.representative.y(), 0.0}, o.label_beams, reach);
    const ScanLabel l = construct_scan_label(scan, dense);
    s.label = l.label;
    for (std::size_t k = 0; k < l.label.size(); ++k) {
      int feature = -1;
      if (l.label[k] == 'M' || l.label[k] == 'D') {
        const int b = l.beam[k];
        const double r = scan.ranges[b];
        const Eigen::Vector2d hit =
            s.representative +
            r * Eigen::Vector2d(std::cos(scan.angles[b]), std::sin(scan.angles[b]));
        double best = std::max(0.05, 4.0 * r * 2.0 * std::numbers::pi / o.label_beams);
        for (int v : s.visible) {
          const double d = (geo.v[v] - hit).norm();
          if (d < best) best = d, feature = v;
        }
      }
      s.features.push_back(feature);
    }
  }

  // Adjacent faces with one label are one sector (seed 000's merge).
  std::vector<int> parent(static_cast<std::size_t>(nf));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (std::size_t c = 0; c < cells; ++c) {
    if (face[c] < 0) continue;
    const int cx = static_cast<int>(c % g.width), cy = static_cast<int>(c / g.width);
    for (int d = 0; d < 2; ++d) {  // east and north neighbours
      const int nx = cx + (d == 0), ny = cy + (d == 1);
      if (!g.contains(nx, ny)) continue;
      const int f = face[g.index(nx, ny)];
      if (f >= 0 && f != face[c] && faces[f].label == faces[face[c]].label) {
        parent[find(f)] = find(face[c]);
      }
    }
  }
  // The largest face of each merged group speaks for it (representative, visible set,
  // features); the cells add up.
  std::vector<int> largest(static_cast<std::size_t>(nf), -1),
      total(static_cast<std::size_t>(nf), 0);
  for (int id = 0; id < nf; ++id) {
    const int root = find(id);
    if (largest[root] < 0 || faces[id].cells > faces[largest[root]].cells) largest[root] = id;
    total[root] += faces[id].cells;
  }
  std::vector<int> sector_of_face(static_cast<std::size_t>(nf), -1);
  for (int id = 0; id < nf; ++id) {
    const int root = find(id);
    if (sector_of_face[root] < 0) {
      sector_of_face[root] = static_cast<int>(out.sectors.size());
      out.sectors.push_back(faces[largest[root]]);
      out.sectors.back().cells = total[root];
    }
    sector_of_face[id] = sector_of_face[root];
  }
  out.sector_of.assign(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    if (face[c] >= 0) out.sector_of[c] = sector_of_face[face[c]];
  }
  for (auto& s : out.sectors) s.area_m2 = s.cells * o.cell_m * o.cell_m;

  // Seed 000 §4.1: labels one turn away from another sector's are ambiguous.
  for (std::size_t a = 0; a < out.sectors.size(); ++a) {
    for (std::size_t b = a + 1; b < out.sectors.size(); ++b) {
      if (cyclic_equal(out.sectors[a].label, out.sectors[b].label)) {
        out.sectors[a].ambiguous = out.sectors[b].ambiguous = true;
      }
    }
  }

  // Seed 000 eq. (10)-(11): alpha = the smallest angle a fully visible edge subtends.
  std::vector<double> alpha(out.sectors.size(), std::numeric_limits<double>::infinity());
  for (std::size_t c = 0; c < cells; ++c) {
    const int s = out.sector_of[c];
    if (s < 0) continue;
    const Eigen::Vector2d p = centre(static_cast<int>(c % g.width), static_cast<int>(c / g.width));
    // Where the robot cannot stand (nearer a wall than the clearance) does not count: at a
    // wall, the wall itself subtends no angle and N_min has no bound (seed 000 §4.2).
    double wall = std::numeric_limits<double>::infinity();
    for (const auto& [i, j] : geo.edges) {
      const Eigen::Vector2d e = geo.v[j] - geo.v[i];
      const double t = std::clamp((p - geo.v[i]).dot(e) / e.squaredNorm(), 0.0, 1.0);
      wall = std::min(wall, (geo.v[i] + t * e - p).norm());
    }
    if (wall < o.clearance_m) continue;
    for (const auto& [i, j] : geo.edges) {
      const bool vi = bits[c * words + i / 64] >> (i % 64) & 1;
      const bool vj = bits[c * words + j / 64] >> (j % 64) & 1;
      if (!vi || !vj) continue;
      const Eigen::Vector2d a = geo.v[i] - p, b = geo.v[j] - p;
      alpha[s] = std::min(alpha[s], std::abs(std::atan2(cross(a, b), a.dot(b))));
    }
  }
  for (std::size_t s = 0; s < out.sectors.size(); ++s) {
    if (!std::isfinite(alpha[s]) || alpha[s] <= 0.0) continue;
    out.sectors[s].n_min = static_cast<int>(std::ceil(6.0 * std::numbers::pi / alpha[s]));
    out.sectors[s].n_min_two = static_cast<int>(std::ceil(4.0 * std::numbers::pi / alpha[s]));
  }
  return out;
}

}  // namespace gridloc
