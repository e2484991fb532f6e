#pragma once
/// What the correlation estimator allocates, estimated before it does (issue 14): the global
/// grids it precomputes from a map and its options, and what one search adds, so that a
/// fine resolution, a tiny heading step or a huge map is an error naming the limit instead
/// of an allocation that takes the machine's memory.
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// The size of one search, for its share of correlation_memory_bytes (all zero: none).
struct SearchSize {
  double translations = 0.0;  ///< cells of the translation lattice
  double headings = 0.0;      ///< headings of the lattice
  /// Cells of one heading's placed local grid (or points of a rigid scan).
  double local_cells = 0.0;
  /// Points of a rigid scan whose cells branch and bound keeps per heading (0: none).
  double point_cells = 0.0;
  /// Every pose is kept: an exhaustive or multiresolution search's scored poses, or a score
  /// volume (score_volume); branch and bound keeps only the leaves it scores.
  bool every_pose = false;
};

/// The cells of the global grid the estimator builds from `map` at `resolution` (m): the
/// map's extent in cells of that size, at least one a side (as resample() makes it).
/// Returned as doubles, before any cast to int.
struct GlobalGridSize {
  double width = 1.0, height = 1.0;  ///< unpadded, cells
  double pad = 0.0;                  ///< cells of padding on every side
  double padded_cells() const { return (width + 2.0 * pad) * (height + 2.0 * pad); }
};
GlobalGridSize global_grid_size(const GridGeometry& map, double resolution, double reach_m);

/// Levels of the bound pyramid branch and bound builds over a global grid of `size`: enough
/// for a block over the whole map, plus one (heading intervals widen blocks up to twice).
/// (CorrelationOptions::max_bound_depth caps it.)
int bound_pyramid_depth(const GlobalGridSize& size);

/// The peak bytes a CorrelationEstimator with `options` holds for a map of geometry `map`
/// whose local grids reach `reach_m` (the padding), plus what a search of size `search`
/// adds. Per cell, measured on the code (engine/src/correlation/memory.cpp lists each term):
///  - the map itself: 1 byte a map cell (CellState);
///  - each global grid built (1, or options.levels for Multires), per padded cell: the
///    padded grid and its arc view as int8 (1 + 1: every global model's values are whole
///    multiples of 1 / int8_scale), and as floats (4 + 4) unless hits_only; while building, per
///    unpadded cell: the resampled map and its flags (1 + 1) and the unpadded grid (4), plus the
///    squared distances of a likelihood field (8);
///  - branch and bound's bound pyramid of the finest grid, per padded cell: a level of an
///    evidence grid 2 bytes (max and min pooled int8), of a likelihood field 10 (their floats
///    too, 4 + 4) times bound_pyramid_depth, plus 1 (the minimum's level of a max-only
///    pyramid; level 0 is the padded grid's), and 8 more while a level is pooled
///    (bound_pyramid_depth, at most options.max_bound_depth when set);
///  - a search: per heading its placed local grid (12 bytes a cell: offset, value, fixed
///    point), a rigid scan's point cells (16 bytes a point) and 300 bytes of bookkeeping;
///    per pose kept (SearchSize::every_pose) 32 bytes (the scored pose and its volume score).
/// Doubles throughout: no size overflows before it is compared with a limit.
/// `hits_only`: the estimator scores a laser's hits alone (no sonar ring, ScanModel::Hits):
/// its padded grids keep no floats and its pyramid only max-pooled int8 levels (1 byte a
/// level) and one level of the minimum.
double correlation_memory_bytes(const GridGeometry& map, const CorrelationOptions& options,
                                double reach_m, const SearchSize& search = {},
                                bool hits_only = false);

}  // namespace gridloc
