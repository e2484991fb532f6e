// What branch and bound bounds and scores with: the bound pyramid (max / min pooled grids,
// also as int8) and the heading grids (each heading's local grid and rigid points' cells).
#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>
#include <string>
#include <utility>

#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/pooling.hpp"

namespace gridloc {
namespace {

constexpr int kMaxDepth = 30;  // 2^h must fit an int

/// The least and the greatest of the first n > 0 values: plain reductions, which vectorize for
/// integers (std::minmax_element's iterators do not).
template <typename T>
std::pair<T, T> min_max(const T* values, std::size_t n) {
  T low = values[0], high = values[0];
  for (std::size_t i = 1; i < n; ++i) {
    low = std::min(low, values[i]);
    high = std::max(high, values[i]);
  }
  return {low, high};
}

/// BoundPyramid::arc_max_all, grid_min_all and abs_max of the first n cells of an arc view
/// and a grid, each value read through `value` (a decode: monotone).
template <typename T, typename Value>
void fill_extremes(BoundPyramid& p, const T* arc, const T* grid, std::size_t n, Value value) {
  if (n == 0) return;
  const auto [arc_min, arc_max] = min_max(arc, n);
  const auto [grid_min, grid_max] = min_max(grid, n);
  p.arc_max_all = value(arc_max);
  p.grid_min_all = value(grid_min);
  for (const T v : {arc_min, arc_max, grid_min, grid_max}) {
    p.abs_max = std::max(p.abs_max, std::abs(value(v)));
  }
}

/// The same of the padded grid, from whichever cells it keeps.
void fill_extremes(BoundPyramid& p, const PaddedGrid& global) {
  const std::size_t n = global.cell_count();
  if (global.has_int8()) {
    fill_extremes(p, global.arc_view8().data(), global.grid8.data(), n,
                  [&global](std::int8_t v) { return global.decode(v); });
  } else {
    fill_extremes(p, global.arc_view().data(), global.grid.cells.data(), n,
                  [](float v) { return v; });
  }
}

/// `grid` with its geometry and no cells: a level the bounds read only as int8.
EvidenceGrid geometry_only(const EvidenceGrid& grid) {
  EvidenceGrid shell;
  shell.geometry = grid.geometry;
  return shell;
}

/// Levels 1..depth of an int8-only pyramid (ternary, or without min levels), each pooled
/// from the one below as int8: its bounds read nothing else, so no float level is made
/// (pooling commutes with the exact int8 map).
void pool_int8_levels(BoundPyramid& p, const PaddedGrid& global, int depth) {
  const int w = global.grid.width(), h = global.grid.height();
  const std::size_t cells = global.cell_count();
  // The padding is zeros: each level pools only the map and the cells it spreads into.
  CellRect arc_nonzero{global.pad, global.pad, global.pad + global.width,
                       global.pad + global.height};
  CellRect min_nonzero = arc_nonzero;
  for (int level = 1; level <= depth; ++level) {
    const int half = 1 << (level - 1);
    // Level 0 is the padded grid's own int8 copy (BoundPyramid::arc_max8).
    Int8Cells arc = level == 1 ? global.arc_view8() : p.arc_max8.back();
    arc_nonzero = max_pool_doubled_in_place(arc.data(), w, h, half, arc_nonzero);
    p.arc_max8.push_back(std::move(arc));
    if (p.min_levels) {
      Int8Cells min = level == 1 ? global.grid8 : p.grid_min8.back();
      min_nonzero = min_pool_doubled_in_place(min.data(), w, h, half, min_nonzero);
      p.grid_min8.push_back(std::move(min));
    } else if (level == 1) {                  // the grid's minimum, standing for every level
      Int8Cells min(global.grid8.size(), 0);  // kGatherSlack zeros at the end
      std::fill_n(min.begin(), cells,
                  static_cast<std::int8_t>(std::lround(p.grid_min_all * p.int8_scale)));
      p.grid_min8.push_back(std::move(min));
    }
    const auto l = static_cast<std::size_t>(level);
    p.arc_max[l] = geometry_only(global.grid);
    p.grid_min[l] = geometry_only(global.grid);
  }
}

/// Levels 1..depth pooled as floats, each kept (and its int8 copy when `int8`).
void pool_float_levels(BoundPyramid& p, const PaddedGrid& global, int depth, bool int8) {
  const auto to_int8 = [&p](const EvidenceGrid& g) {
    return to_int8_with_slack(g.cells, p.int8_scale);
  };
  EvidenceGrid arc_work = geometry_only(global.grid), min_work = geometry_only(global.grid);
  arc_work.cells = global.arc_float_cells();
  min_work.cells = global.float_cells();
  // Without min levels, level 1 holds the whole grid's minimum and stands for every level.
  if (!p.min_levels) min_work.cells.assign(min_work.cells.size(), p.grid_min_all);
  for (int h = 1; h <= depth; ++h) {  // each level from the one below: 2 ops per cell
    const auto l = static_cast<std::size_t>(h);
    const int half = 1 << (h - 1);
    const bool own_min = p.min_levels || h == 1;
    max_pool_doubled_in_place(arc_work, half);
    if (p.min_levels) min_pool_doubled_in_place(min_work, half);
    if (int8) {
      p.arc_max8.push_back(to_int8(arc_work));
      if (own_min) p.grid_min8.push_back(to_int8(min_work));
    }
    p.arc_max[l] = arc_work;
    p.grid_min[l] = own_min ? min_work : geometry_only(min_work);
  }
}

}  // namespace

BoundPyramid make_bound_pyramid(const PaddedGrid& global, int depth, PyramidLevels levels) {
  if (depth < 0 || depth > kMaxDepth) {
    throw Error("bound pyramid: depth = " + std::to_string(depth) + " must lie in [0, " +
                std::to_string(kMaxDepth) + "]");
  }
  BoundPyramid p;
  p.min_levels = levels == PyramidLevels::MaxAndMin;
  p.pad = global.pad;
  p.width = global.width;
  p.height = global.height;
  p.arc_max.resize(static_cast<std::size_t>(depth) + 1);
  p.grid_min.resize(static_cast<std::size_t>(depth) + 1);
  fill_extremes(p, global);
  // The padded grid's int8 scale serves its arc view too; pooling keeps values: levels too.
  const bool int8 = global.has_int8();
  if (int8) {  // level 0 is the padded grid's int8 cells, not a second copy
    p.int8_scale = global.int8_scale;
    p.arc_max8.emplace_back();
    p.grid_min8.emplace_back();
  }
  // A ternary pyramid's bounds read only its int8 levels (block_bound, interval_sum): 5x
  // less memory than float levels, and no page of a float grid to fault in per level.
  // So is an int8 pyramid without min levels (a laser's hits: fixed-point points only).
  p.float_levels = !(p.ternary() || (p.has_int8() && !p.min_levels));
  if (!p.float_levels) {
    pool_int8_levels(p, global, depth);
  } else {
    pool_float_levels(p, global, depth, int8);
  }
  return p;
}

int bound_depth_for(const Lattice& lattice) {
  const int n = std::max(lattice.x1 - lattice.x0 + 1, lattice.y1 - lattice.y0 + 1);
  int depth = 0;
  while (depth < kMaxDepth && (1 << depth) < n) ++depth;
  return depth;
}

namespace {

/// Runs `make` once, the first time any thread gets here with `made` false: a made grid
/// costs one atomic load. `make` may throw; `made` then stays false.
template <typename Make>
void make_once(std::atomic<bool>& made, std::mutex& making, Make&& make) {
  if (made.load(std::memory_order_acquire)) return;
  const std::lock_guard<std::mutex> lock(making);
  if (made.load(std::memory_order_relaxed)) return;
  make();
  made.store(true, std::memory_order_release);
}

}  // namespace

HeadingGrids::HeadingGrids(const Lattice& lattice, const SearchLevel& finest)
    : lattice_(lattice),
      level_(finest),
      entries_(std::make_unique<Entry[]>(static_cast<std::size_t>(std::max(lattice.headings, 0)))) {
  if (finest.global == nullptr) throw Error("branch and bound: the search level has no grid");
  if (finest.points != nullptr) {
    const double res = finest.global->grid.geometry.resolution;
    if (finest.points->max_norm / res + 1.0 > finest.global->pad) {
      std::ostringstream m;
      m << "branch and bound: the scan's points reach " << finest.points->max_norm
        << " m, beyond the padding of " << finest.global->pad << " cells";
      throw Error(m.str());
    }
  }
}

const PlacedLocalGrid& HeadingGrids::placed(int it) const {
  Entry& e = entries_[static_cast<std::size_t>(it)];
  make_once(e.placed_made, e.making, [&] {
    if (level_.points != nullptr) {  // make_local's grid, without the detour (tested equal)
      e.placed = place_points(*level_.points, lattice_.theta(it), *level_.global);
      return;
    }
    const SparseLocalGrid local = level_.make_local(lattice_.theta(it), Eigen::Vector2d::Zero());
    const int extent = local.size() > 0 ? local.extent() : 0;
    if (extent > level_.global->pad) {
      throw Error("branch and bound: local grid extent " + std::to_string(extent) +
                  " cells (heading " + std::to_string(it) + ") exceeds the padding " +
                  std::to_string(level_.global->pad));
    }
    e.placed = place(local, *level_.global);
  });
  return e.placed;
}

const HeadingGrids::PointCells& HeadingGrids::point_cells(int it) const {
  Entry& e = entries_[static_cast<std::size_t>(it)];
  make_once(e.cells_made, e.making, [&] {
    const ScanPoints& p = *level_.points;
    const double theta = lattice_.theta(it);
    const double c = std::cos(theta), s = std::sin(theta);
    const double inv = 1.0 / level_.global->grid.geometry.resolution;
    const std::ptrdiff_t width = level_.global->grid.width();
    // Sorted by offset: a bound then walks the grid's rows in order.
    std::vector<std::pair<std::ptrdiff_t, Eigen::Vector2i>> hits, frees;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const Eigen::Vector2i cell = point_cell(p, k, c, s, inv);
      (k < p.hit_count ? hits : frees).push_back({cell.y() * width + cell.x(), cell});
    }
    auto fill = [](auto& items, auto& offset, auto& xs, auto& ys) {
      std::sort(items.begin(), items.end(),
                [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [o, cell] : items) {
        offset.push_back(o);
        xs.push_back(cell.x());
        ys.push_back(cell.y());
      }
    };
    fill(hits, e.cells.hit_offset, e.cells.hit_x, e.cells.hit_y);
    fill(frees, e.cells.free_offset, e.cells.free_x, e.cells.free_y);
  });
  return e.cells;
}

void HeadingGrids::make_all() const {
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic) num_threads(level_.threads) if (level_.threads > 1)
  for (int it = 0; it < lattice_.headings; ++it) {
    try {
      placed(it);
    } catch (...) {
#pragma omp critical(gridloc_make_all)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace gridloc
