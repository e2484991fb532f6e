#pragma once
/// Max / min pooling of a grid over square blocks: the bound grids of an exact
/// branch-and-bound search (DESIGN.md, "Global grid").
#include <cstdint>

#include "gridloc/grids/grid.hpp"

namespace gridloc {

/// Cell (x, y) of the result = max of g over the block [x, x + size) x [y, y + size), clipped
/// at the grid's edge; same geometry as g. O(cells) whatever `size`: a separable sliding-window
/// maximum (van Herk / Gil-Werman). Throws gridloc::Error if size < 1.
Grid<float> max_pool(const Grid<float>& g, int size);
/// As max_pool, with the minimum.
Grid<float> min_pool(const Grid<float>& g, int size);

/// max_pool(g, 2 * size) from pooled = max_pool(g, size), exactly, in two vectorized passes of
/// one max per cell each: how a pyramid of sizes 2, 4, 8, ... is built fast. Throws
/// gridloc::Error if size < 1.
Grid<float> max_pool_doubled(const Grid<float>& pooled, int size);
/// As max_pool_doubled, with the minimum.
Grid<float> min_pool_doubled(const Grid<float>& pooled, int size);

/// max_pool_doubled in place, with no allocation: `pooled` = max_pool(g, size) becomes
/// max_pool(g, 2 * size). Throws gridloc::Error if size < 1.
void max_pool_doubled_in_place(Grid<float>& pooled, int size);
/// As max_pool_doubled_in_place, with the minimum.
void min_pool_doubled_in_place(Grid<float>& pooled, int size);
/// The same on int8 cells (row-major, `width` x `height`): pooling commutes with any
/// increasing map of the values, so pooled int8 copies of a grid equal int8 copies of its
/// pooled grid (how a bound pyramid kept as int8 is built without float levels).
void max_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size);
void min_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size);

/// Cells [x0, x1) x [y0, y1) of a grid.
struct CellRect {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
};
/// The same on a grid whose cells outside `nonzero` are all zero (a padded map's border):
/// only that rectangle grown by `size` on its low sides can change, so only it is pooled (the
/// same cells as pooling the whole grid). Returns that grown rectangle, the nonzero cells of
/// the result, for the next level.
CellRect max_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size,
                                   CellRect nonzero);
CellRect min_pool_doubled_in_place(std::int8_t* cells, int width, int height, int size,
                                   CellRect nonzero);

/// Plain O(cells * size^2) loops computing what max_pool does: the oracle for tests.
Grid<float> max_pool_reference(const Grid<float>& g, int size);
/// Plain O(cells * size^2) loops computing what min_pool does: the oracle for tests.
Grid<float> min_pool_reference(const Grid<float>& g, int size);

}  // namespace gridloc
