// The correlation estimator's memory, estimated before it is allocated (issue 14). The bytes
// per cell follow the code that allocates them: make_global_grid (grids/src/evidence.cpp),
// pad_grid (search.cpp), make_bound_pyramid (bound_pyramid.cpp), HeadingGrids and the
// searches' scored poses; bench/RESULTS.md compares the estimate with measured peaks.
#include "gridloc/engine/correlation/memory.hpp"

#include <algorithm>
#include <cmath>

namespace gridloc {
namespace {

constexpr double kMapBytes = 1.0;            // CellState per map cell
constexpr double kPaddedGridBytes = 2.0;     // the grid and its arc view as int8: every
                                             // global model's values are whole multiples
constexpr double kPaddedFloatBytes = 8.0;    // and as floats, unless a laser's hits alone
constexpr double kBuildBytes = 6.0;          // resampled map + flags (uint8) + unpadded float
constexpr double kFieldBuildBytes = 8.0;     // a likelihood field's squared distances (double)
constexpr double kPyramidLevelBytes = 10.0;  // arc_max + grid_min (float) + int8 copies
constexpr double kTernaryLevelBytes = 2.0;   // an evidence grid's levels: int8 only, pooled
                                             // in the two working grids of kPoolingBytes
constexpr double kPyramidBaseBytes = 1.0;    // level 0 is the padded grid's: 1 B for the
                                             // minimum's level of a max-only pyramid
constexpr double kPoolingBytes = 8.0;        // the two working grids pooled in place
constexpr double kHitsLevelBytes = 1.0;      // a laser's hits alone: max-pooled int8 levels,
constexpr double kHitsPoolingBytes = 2.0;    // each pooled from a copy of the one below
constexpr double kLocalCellBytes = 12.0;     // PlacedLocalGrid: offset, value, fixed (4 each)
constexpr double kPointCellBytes = 16.0;     // PointCells: offset (8), x and y (4 + 4)
constexpr double kHeadingBytes = 300.0;      // HeadingGrids::Entry and the search's node
constexpr double kPoseBytes = 32.0;          // a scored LatticePose (24) and its volume score

double level_resolution(double finest, int l) {
  return finest * static_cast<double>(1 << l);
}

/// One global grid of the estimator: what it keeps, and what building it needs on top.
struct LevelBytes {
  double kept = 0.0, building = 0.0;
};

LevelBytes level_bytes(const GridGeometry& map, const CorrelationOptions& options, double res,
                       double reach_m, bool hits_only) {
  const GlobalGridSize size = global_grid_size(map, res, reach_m);
  const double cells = size.width * size.height;
  const double build =
      kBuildBytes + (options.global == GlobalModel::LikelihoodField ? kFieldBuildBytes : 0.0);
  const double padded = kPaddedGridBytes + (hits_only ? 0.0 : kPaddedFloatBytes);
  return {padded * size.padded_cells(), build * cells};
}

/// The bound pyramid of the finest grid: what it keeps, and what pooling it needs on top.
LevelBytes pyramid_bytes(const GridGeometry& map, const CorrelationOptions& options, double reach_m,
                         bool hits_only) {
  if (options.strategy != SearchStrategy::BranchAndBound) return {};
  const GlobalGridSize size = global_grid_size(map, options.resolution, reach_m);
  const double padded = size.padded_cells();
  const int whole_map = bound_pyramid_depth(size);
  const double depth =
      options.max_bound_depth > 0 ? std::min(whole_map, options.max_bound_depth) : whole_map;
  if (hits_only) {  // max-pooled int8 levels and one level of the minimum, whatever the grid
    return {(kHitsLevelBytes * depth + kPyramidBaseBytes) * padded, kHitsPoolingBytes * padded};
  }
  // A likelihood field's levels keep their floats; an evidence grid's (-1/0/1) only int8.
  if (options.global == GlobalModel::LikelihoodField) {
    return {(kPyramidLevelBytes * depth + kPyramidBaseBytes) * padded, kPoolingBytes * padded};
  }
  return {(kTernaryLevelBytes * depth + kPyramidBaseBytes) * padded, kPoolingBytes * padded};
}

double search_bytes(const SearchSize& search) {
  const double per_heading =
      kHeadingBytes + kLocalCellBytes * search.local_cells + kPointCellBytes * search.point_cells;
  const double poses = search.every_pose ? search.translations * search.headings : 0.0;
  return search.headings * per_heading + kPoseBytes * poses;
}

}  // namespace

GlobalGridSize global_grid_size(const GridGeometry& map, double resolution, double reach_m) {
  GlobalGridSize size;
  size.width = std::max(1.0, std::ceil(map.width * map.resolution / resolution - 1e-9));
  size.height = std::max(1.0, std::ceil(map.height * map.resolution / resolution - 1e-9));
  size.pad = std::ceil(reach_m / resolution) + 3.0;
  return size;
}

int bound_pyramid_depth(const GlobalGridSize& size) {
  const double side = std::max(size.width, size.height);
  int depth = 0;
  while (depth < 31 && std::ldexp(1.0, depth) < side) ++depth;
  return depth + 1;
}

double correlation_memory_bytes(const GridGeometry& map, const CorrelationOptions& options,
                                double reach_m, const SearchSize& search, bool hits_only) {
  const int built = options.strategy == SearchStrategy::Multires ? options.levels : 1;
  double kept = kMapBytes * map.width * map.height, building = 0.0;
  for (int l = 0; l < built; ++l) {
    const LevelBytes level =
        level_bytes(map, options, level_resolution(options.resolution, l), reach_m, hits_only);
    building = std::max(building, level.building);  // one level is built at a time
    kept += level.kept;
  }
  const LevelBytes pyramid = pyramid_bytes(map, options, reach_m, hits_only);
  building = std::max(building, pyramid.building);
  kept += pyramid.kept;
  return kept + building + search_bytes(search);
}

}  // namespace gridloc
