#pragma once
/// Dense row-major grids: occupancy maps and evidence grids.
#include <cstdint>
#include <vector>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// A dense grid of T in row-major order (row iy, column ix).
template <typename T>
struct Grid {
  GridGeometry geometry;
  std::vector<T> cells;

  Grid() = default;
  Grid(const GridGeometry& g, T fill) : geometry(g), cells(g.size(), fill) {}

  int width() const { return geometry.width; }
  int height() const { return geometry.height; }
  T& at(int ix, int iy) { return cells[geometry.index(ix, iy)]; }
  const T& at(int ix, int iy) const { return cells[geometry.index(ix, iy)]; }
  /// Pointer to the first cell of row iy, for hot loops.
  T* row(int iy) { return cells.data() + geometry.index(0, iy); }
  const T* row(int iy) const { return cells.data() + geometry.index(0, iy); }
};

enum class CellState : std::uint8_t { Free, Occupied, Unknown };

/// A three-state map of the environment.
using OccupancyMap = Grid<CellState>;
/// Evidence: occupied > 0, free < 0, unknown 0 (seed 001 §2).
using EvidenceGrid = Grid<float>;

}  // namespace gridloc
