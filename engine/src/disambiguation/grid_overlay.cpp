#include "gridloc/engine/disambiguation/grid_overlay.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "grid_useful.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// How far (cells) an anchor outside the cells free in every map may be moved to one.
constexpr int kAnchorSnapCells = 3;
/// The most lattice cells an overlay holds (its per-cell masks, counts and Dijkstra arrays
/// take about 30 bytes each).
constexpr double kMaxLatticeCells = 5e7;

using Box = Eigen::AlignedBox2d;

std::string point_text(const Eigen::Vector2d& p) {
  return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
}

void check_inputs(const OccupancyMap& map, const std::vector<Pose2>& hypotheses, double range,
                  const Eigen::Vector2d& anchor) {
  if (map.width() <= 0 || map.height() <= 0 || !(map.geometry.resolution > 0.0)) {
    throw Error("make_grid_overlay: the map is empty");
  }
  if (hypotheses.empty()) throw Error("make_grid_overlay: no hypotheses");
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const Pose2& h = hypotheses[i];
    if (!std::isfinite(h.x) || !std::isfinite(h.y) || !std::isfinite(h.theta)) {
      throw Error("make_grid_overlay: hypothesis " + std::to_string(i) + " is not finite");
    }
  }
  if (!(range > 0.0)) {
    throw Error("make_grid_overlay: range must be positive, got " + std::to_string(range));
  }
  if (!anchor.allFinite()) throw Error("make_grid_overlay: anchor is not finite");
}

[[noreturn]] void throw_anchor_not_free(const Eigen::Vector2d& anchor) {
  throw Error("make_grid_overlay: the anchor " + point_text(anchor) +
              " (start frame) is not in a cell free in every hypothesis's map");
}

/// The affine map from a start-frame point (m) to the map's grid coordinates in cells under
/// hypothesis h: q = A p + b, A = R(theta - yaw) / res, b = R(-yaw)(t - origin) / res.
struct ToMapCells {
  Eigen::Matrix2d a;
  Eigen::Vector2d b;
};

ToMapCells to_map_cells(const GridGeometry& g, const Pose2& h) {
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(h.theta - g.yaw).toRotationMatrix();
  const Eigen::Matrix2d unyaw = Eigen::Rotation2Dd(-g.yaw).toRotationMatrix();
  return {rotation / g.resolution, unyaw * (Eigen::Vector2d(h.x, h.y) - g.origin) / g.resolution};
}

/// The bounding box of the map's Free cells in its grid frame (m); empty when none is free.
Box free_cells_box(const OccupancyMap& map) {
  Box box;  // empty
  const double res = map.geometry.resolution;
  for (int iy = 0; iy < map.height(); ++iy) {
    const CellState* row = map.row(iy);
    for (int ix = 0; ix < map.width(); ++ix) {
      if (row[ix] != CellState::Free) continue;
      box.extend(Eigen::Vector2d(ix * res, iy * res));
      box.extend(Eigen::Vector2d((ix + 1) * res, (iy + 1) * res));
    }
  }
  return box;
}

/// The start-frame bounding box of a grid-frame box under hypothesis h.
Box start_frame_box(const GridGeometry& g, const Box& grid_box, const Pose2& h) {
  Box box;
  for (const Box::CornerType corner :
       {Box::BottomLeft, Box::BottomRight, Box::TopLeft, Box::TopRight}) {
    const Eigen::Vector2d c = grid_box.corner(corner);
    const Pose2 world = g.to_world_frame({c.x(), c.y(), 0.0});
    box.extend(to_start_frame(h, Eigen::Vector2d(world.x, world.y)));
  }
  return box;
}

/// The lattice covering every cell whose centre lies in `box`, plus one cell each side; cell
/// corners at integer multiples of res.
GridGeometry lattice_over(const Box& box, double res) {
  const int x0 = static_cast<int>(std::ceil(box.min().x() / res - 0.5)) - 1;
  const int y0 = static_cast<int>(std::ceil(box.min().y() / res - 0.5)) - 1;
  const int x1 = static_cast<int>(std::floor(box.max().x() / res - 0.5)) + 1;
  const int y1 = static_cast<int>(std::floor(box.max().y() / res - 0.5)) + 1;
  GridGeometry lattice;
  lattice.resolution = res;
  lattice.origin = Eigen::Vector2d(x0 * res, y0 * res);
  lattice.width = x1 - x0 + 1;
  lattice.height = y1 - y0 + 1;
  return lattice;
}

/// The start-frame lattice: only the intersection of the maps' free boxes can hold OI.
GridGeometry make_lattice(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                          const Eigen::Vector2d& anchor) {
  const Box free_box = free_cells_box(map);
  if (free_box.isEmpty()) throw_anchor_not_free(anchor);
  Box common = start_frame_box(map.geometry, free_box, hypotheses.front());
  for (const Pose2& h : hypotheses) {
    common = common.intersection(start_frame_box(map.geometry, free_box, h));
  }
  if (common.isEmpty()) throw_anchor_not_free(anchor);
  return lattice_over(common, map.geometry.resolution);
}

/// The anchor's cell, or when it is not free in every map the nearest cell within
/// kAnchorSnapCells that is (an estimated pose a hair inside a wall); {-1, -1} when none is.
Cell snapped_anchor(const GridGeometry& lattice, const std::vector<int>& free_maps, int all,
                    const Cell& anchor) {
  const auto free_in_all = [&](int ix, int iy) {
    return lattice.contains(ix, iy) && free_maps[lattice.index(ix, iy)] == all;
  };
  Cell best{-1, -1};
  int best_distance = std::numeric_limits<int>::max();
  for (int dy = -kAnchorSnapCells; dy <= kAnchorSnapCells; ++dy) {
    for (int dx = -kAnchorSnapCells; dx <= kAnchorSnapCells; ++dx) {
      const int distance = dx * dx + dy * dy;
      if (distance < best_distance && free_in_all(anchor.ix + dx, anchor.iy + dy)) {
        best = {anchor.ix + dx, anchor.iy + dy};
        best_distance = distance;
      }
    }
  }
  return best;
}

/// Per lattice cell, in how many hypotheses' maps its centre falls on a Free cell.
std::vector<int> count_free_maps(const OccupancyMap& map, const GridGeometry& lattice,
                                 const std::vector<Pose2>& hypotheses) {
  std::vector<int> count(lattice.size(), 0);
  for (const Pose2& h : hypotheses) {
    const ToMapCells t = to_map_cells(map.geometry, h);
    for (int iy = 0; iy < lattice.height; ++iy) {
      for (int ix = 0; ix < lattice.width; ++ix) {
        const Eigen::Vector2d q = t.a * (lattice.origin + lattice.cell_center(ix, iy)) + t.b;
        const int mx = static_cast<int>(std::floor(q.x()));
        const int my = static_cast<int>(std::floor(q.y()));
        if (map.geometry.contains(mx, my) && map.at(mx, my) == CellState::Free) {
          ++count[lattice.index(ix, iy)];
        }
      }
    }
  }
  return count;
}

constexpr int kSteps4[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};

/// OI: the 4-connected component of cells free in every map holding `start` (seed 002 §IV step
/// 5). Returns the cell count.
int grow_oi(const GridGeometry& lattice, const std::vector<int>& free_maps, int all,
            const Cell& start, std::vector<std::uint8_t>& in_oi) {
  std::deque<Cell> frontier{start};
  in_oi[lattice.index(start.ix, start.iy)] = 1;
  int count = 1;
  while (!frontier.empty()) {
    const Cell c = frontier.front();
    frontier.pop_front();
    for (const auto& step : kSteps4) {
      const int nx = c.ix + step[0], ny = c.iy + step[1];
      if (!lattice.contains(nx, ny)) continue;
      const std::size_t n = lattice.index(nx, ny);
      if (in_oi[n] || free_maps[n] != all) continue;
      in_oi[n] = 1;
      ++count;
      frontier.push_back({nx, ny});
    }
  }
  return count;
}

/// Internal cells: OI cells with a 4-neighbour outside OI that some map has free (seed 002
/// Fig. 5's internal edges: beyond them the hypotheses disagree). Returns the count.
int mark_internal(GridOverlay& overlay) {
  const GridGeometry& g = overlay.grid;
  int count = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (!overlay.in_oi[g.index(ix, iy)]) continue;
      for (const auto& step : kSteps4) {
        const int nx = ix + step[0], ny = iy + step[1];
        if (!g.contains(nx, ny)) continue;
        const std::size_t n = g.index(nx, ny);
        if (!overlay.in_oi[n] && overlay.in_any[n]) {
          overlay.internal[g.index(ix, iy)] = 1;
          ++count;
          break;
        }
      }
    }
  }
  return count;
}

}  // namespace

Cell GridOverlay::cell_of(const Eigen::Vector2d& p) const {
  return grid.cell_of(p.x() - grid.origin.x(), p.y() - grid.origin.y());
}

Eigen::Vector2d GridOverlay::cell_center(const Cell& cell) const {
  return grid.origin + grid.cell_center(cell.ix, cell.iy);
}

bool GridOverlay::oi_contains(const Eigen::Vector2d& p) const {
  const Cell c = cell_of(p);
  return grid.contains(c.ix, c.iy) && in_oi[grid.index(c.ix, c.iy)] != 0;
}

GridOverlay make_grid_overlay(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                              double range, const Eigen::Vector2d& anchor) {
  check_inputs(map, hypotheses, range, anchor);
  GridOverlay overlay;
  overlay.grid = make_lattice(map, hypotheses, anchor);  // seed 002 §IV-C step 4
  if (static_cast<double>(overlay.grid.width) * overlay.grid.height > kMaxLatticeCells) {
    throw Error("make_grid_overlay: the start-frame lattice would hold " +
                std::to_string(static_cast<double>(overlay.grid.width) * overlay.grid.height) +
                " cells, more than 5e7 (a map this large needs a coarser resolution)");
  }
  overlay.hypotheses = hypotheses;
  overlay.range = range;
  const std::vector<int> free_maps = count_free_maps(map, overlay.grid, hypotheses);
  const int all = static_cast<int>(hypotheses.size());
  overlay.anchor_cell = snapped_anchor(overlay.grid, free_maps, all, overlay.cell_of(anchor));
  const Cell& a = overlay.anchor_cell;
  if (!overlay.grid.contains(a.ix, a.iy)) throw_anchor_not_free(anchor);
  const std::size_t cells = overlay.grid.size();
  overlay.in_any.resize(cells);
  for (std::size_t i = 0; i < cells; ++i) overlay.in_any[i] = free_maps[i] > 0 ? 1 : 0;
  overlay.in_oi.assign(cells, 0);
  overlay.internal.assign(cells, 0);
  overlay.useful.assign(cells, 0);
  overlay.oi_count = grow_oi(overlay.grid, free_maps, all, a, overlay.in_oi);  // step 5
  overlay.internal_count = mark_internal(overlay);
  overlay.useful_count = mark_useful(overlay);  // seed 002 §IV-D steps 5-6
  return overlay;
}

std::vector<Eigen::Vector2d> sample_overlay_cells(const GridOverlay& overlay, bool useful,
                                                  int count, Rng& rng) {
  if (count < 0) {
    throw Error("sample_overlay_cells: count must be >= 0, got " + std::to_string(count));
  }
  const std::vector<std::uint8_t>& set = useful ? overlay.useful : overlay.in_oi;
  std::vector<std::size_t> members;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set[i]) members.push_back(i);
  }
  std::vector<Eigen::Vector2d> points;
  if (members.empty()) return points;
  const GridGeometry& g = overlay.grid;
  points.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const double pick = rng.uniform() * static_cast<double>(members.size());
    const std::size_t i = members[std::min(members.size() - 1, static_cast<std::size_t>(pick))];
    const int ix = static_cast<int>(i % static_cast<std::size_t>(g.width));
    const int iy = static_cast<int>(i / static_cast<std::size_t>(g.width));
    // seed 002 §IV-A: uniform in OI; kept 1e-9 off the cell's sides so rounding cannot move
    // a point into a neighbour
    const double jx = rng.uniform(1e-9, 1.0 - 1e-9), jy = rng.uniform(1e-9, 1.0 - 1e-9);
    points.push_back(g.origin +
                     Eigen::Vector2d((ix + jx) * g.resolution, (iy + jy) * g.resolution));
  }
  return points;
}

}  // namespace gridloc
