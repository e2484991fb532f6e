#pragma once
/// Exact branch and bound over translations (DESIGN.md, "Global grid"): blocks of 2^h x 2^h
/// translations are bounded from above with max / min pooled global grids and pruned
/// against the best pose found so far. Returns what search_exhaustive returns, bit for bit,
/// while scoring far fewer poses.
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <optional>
#include <vector>

#include "gridloc/engine/correlation_search.hpp"
#include "gridloc/grids/grid.hpp"

namespace gridloc {

/// Bound grids of one PaddedGrid, built once. At level h (blocks of 2^h x 2^h translations),
/// arc_max[h] is the PaddedGrid's arc_view max-pooled and grid_min[h] its grid min-pooled,
/// cell (x, y) covering [x, x + 2^h) x [y, y + 2^h); both keep the padded geometry, so a
/// PlacedLocalGrid's offsets apply unchanged. Level 0 is the PaddedGrid itself and is not
/// copied: arc_max[0] and grid_min[0] are empty. A plain value, safe to copy or move.
struct BoundPyramid {
  std::vector<EvidenceGrid> arc_max;   ///< [h] for h = 1..depth; [0] empty
  std::vector<EvidenceGrid> grid_min;  ///< [h] for h = 1..depth; [0] empty
  int pad = 0;                         ///< the source PaddedGrid's pad, width and height:
  int width = 0;                       ///< checked against the grid searched
  int height = 0;

  /// The top level h (0 when only level 0 exists).
  int depth() const { return static_cast<int>(arc_max.size()) - 1; }
};

/// Builds levels 1..depth of `global`'s bound pyramid (depth >= 0; throws gridloc::Error
/// otherwise), O(padded cells) per level. Needs no padding beyond what score() needs
/// (pad >= the local grids' extent), whatever the depth: the search only makes blocks that
/// start inside the lattice, and the pooled windows are clipped at the padded grid's edge.
BoundPyramid make_bound_pyramid(const PaddedGrid& global, int depth);

/// The smallest depth whose top-level blocks cover the lattice's translations in one block
/// per heading: ceil(log2(max(columns, rows))); a deeper pyramid adds nothing for it.
int bound_depth_for(const Lattice& lattice);

/// Upper bound on score(global, local, x, y) for every (x, y) in [ix, ix + 2^h) x
/// [iy, iy + 2^h) that lies in the map, at level 1 <= h <= pyramid.depth(); (ix, iy) must
/// lie in the map. Computed exactly as score() computes a score, with pooled values: each
/// term is then >= the matching score term after float rounding, and so is each partial sum
/// after double rounding (rounding is monotone), so the bound holds bit for bit, no epsilon.
inline double block_bound(const BoundPyramid& pyramid, const PlacedLocalGrid& local, int h, int ix,
                          int iy) {
  const auto& arc_grid = pyramid.arc_max[static_cast<std::size_t>(h)];
  const std::ptrdiff_t origin =
      static_cast<std::ptrdiff_t>(iy + pyramid.pad) * arc_grid.width() + (ix + pyramid.pad);
  return correlate(arc_grid.cells.data() + origin,
                   pyramid.grid_min[static_cast<std::size_t>(h)].cells.data() + origin, local);
}

/// Poses left out of a search: those within `radius_cells` (Euclidean, in cells) and
/// `radius_headings` (heading indices) of `center`. Used to find the best pose *distinct*
/// from a winner, exactly.
struct Exclusion {
  LatticePose center;
  double radius_cells = 0.0;
  int radius_headings = 0;

  bool contains(int ix, int iy, int it) const {
    return std::abs(it - center.it) <= radius_headings &&
           std::hypot(ix - center.ix, iy - center.iy) <= radius_cells;
  }
  /// True when every translation of [x0, x1] x [y0, y1] at heading it is excluded (a disc
  /// holds a rectangle when it holds its corners).
  bool contains_block(int it, int x0, int y0, int x1, int y1) const {
    return contains(x0, y0, it) && contains(x1, y0, it) && contains(x0, y1, it) &&
           contains(x1, y1, it);
  }
};

/// Exact branch-and-bound search over the whole lattice on the finest level: the same best
/// pose and score as search_exhaustive(lattice, finest), ties to the lowest (it, iy, ix).
/// `pyramid` must come from *finest.global (checked by geometry only); the lattice must be
/// non-empty and inside the map, and every local grid's extent <= pad (gridloc::Error
/// otherwise). Any depth is exact; the top level used is min(pyramid.depth(),
/// bound_depth_for(lattice)), so one deep pyramid serves small and large windows alike.
/// Best first over the blocks of all headings (highest bound, then lowest first pose); a
/// block is dropped when its bound is below the best score so far, or equal to it while the
/// block holds no pose of lower index; the search ends when the best open block is dropped.
/// Result: `scored` holds only the leaf poses scored exactly, in scoring order (a partial
/// score volume: pruned poses are missing, so second peaks read from it are lower bounds
/// of the true ones); poses_scored counts them; cells_scored counts local cells multiplied
/// by leaf scores and by block bounds alike. finest.threads builds the headings' local
/// grids in parallel; the search itself runs on one thread. With `exclude`, the poses it
/// contains are never candidates (the result is the exhaustive best among the others; an
/// empty result has poses_scored == 0).
SearchResult search_branch_and_bound(const Lattice& lattice, const SearchLevel& finest,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude = std::nullopt);

/// Every heading's local grid of the lattice, made by finest.make_local and placed on
/// *finest.global (in parallel when finest.threads > 1); throws gridloc::Error when a grid
/// reaches beyond the padding. Lets several searches share one set of local grids.
std::vector<PlacedLocalGrid> place_headings(const Lattice& lattice, const SearchLevel& finest);

/// The same search on local grids already placed on `global` (one per heading).
SearchResult search_branch_and_bound(const Lattice& lattice, const PaddedGrid& global,
                                     const std::vector<PlacedLocalGrid>& placed,
                                     const BoundPyramid& pyramid,
                                     const std::optional<Exclusion>& exclude = std::nullopt);

}  // namespace gridloc
