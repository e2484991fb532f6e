#pragma once
/// The correlation search of seed 001 §2 as free functions: score S = sum L * G of a local
/// grid placed on a global grid, over a lattice of cells x headings.
#include <cstddef>
#include <functional>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/local_grid.hpp"

namespace gridloc {

/// A global grid padded with `pad` unknown (0) cells on every side, so that any local grid
/// of extent <= pad placed on any cell of the map needs no bounds checks.
struct PaddedGrid {
  EvidenceGrid grid;  ///< the padded grid; map cell (ix, iy) is grid cell (ix + pad, iy + pad)
  int pad = 0;
  int width = 0;   ///< the unpadded map's width, cells
  int height = 0;  ///< the unpadded map's height, cells
};

PaddedGrid pad_grid(const EvidenceGrid& grid, int pad);

/// Reference score: sum over local cells of value * global cell, cells outside the grid
/// counting 0. Plain loops, kept as the oracle for the fast path.
double score_reference(const EvidenceGrid& global, const SparseLocalGrid& local, int cx, int cy);

/// A local grid turned into flat offsets in one padded grid (computed once per heading).
struct PlacedLocalGrid {
  std::vector<std::ptrdiff_t> offset;
  std::vector<float> value;
};

PlacedLocalGrid place(const SparseLocalGrid& local, const PaddedGrid& global);

/// Fast score of `local` with the robot on map cell (cx, cy); the cell must lie in the map
/// and the local grid's extent must not exceed the padding.
inline double score(const PaddedGrid& global, const PlacedLocalGrid& local, int cx, int cy) {
  const float* base = global.grid.cells.data() +
                      static_cast<std::ptrdiff_t>(cy + global.pad) * global.grid.width() +
                      (cx + global.pad);
  double s = 0.0;
  const std::size_t n = local.value.size();
  for (std::size_t k = 0; k < n; ++k) s += static_cast<double>(local.value[k] * base[local.offset[k]]);
  return s;
}

/// A candidate of the search lattice: map cell and heading index.
struct LatticePose {
  int ix = 0;
  int iy = 0;
  int it = 0;
  double score = 0.0;
};

/// The translation x heading lattice of one search, in finest-level cells.
struct Lattice {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  ///< inclusive cell ranges, clipped to the map
  int headings = 1;                    ///< heading index it in [0, headings)
  std::function<double(int it)> theta;  ///< heading of index it, grid frame (rad)
};

/// One resolution level of the search: padded global grid, resolution and a maker of local
/// grids for a heading index (built directly at this level's resolution, seed 001 §2).
struct SearchLevel {
  const PaddedGrid* global = nullptr;
  std::function<SparseLocalGrid(int it)> make_local;
};

struct SearchResult {
  LatticePose best;
  std::vector<LatticePose> scored;  ///< every finest-level pose scored, in scoring order
  long long poses_scored = 0;
  long long cells_scored = 0;
};

/// Exhaustive search over the whole lattice on the finest level. Ties go to the lowest index
/// in (it, iy, ix) order.
SearchResult search_exhaustive(const Lattice& lattice, const SearchLevel& finest);

/// Multiresolution search (seed 001 §2): levels[l] has cells 2^l times the finest. The
/// coarsest level scores its whole lattice; every finer level scores the children (+-1 cell
/// margin, +-1 heading) of the `keep` best poses of the level above. Ties as exhaustive.
SearchResult search_multires(const Lattice& lattice, const std::vector<SearchLevel>& levels,
                             int keep);

}  // namespace gridloc
