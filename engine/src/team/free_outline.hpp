#pragma once
// The outline of an occupancy map's free space, traced along cell edges. Internal to the
// engine (map_features.cpp); no OpenCV, so a sonar-only user links nothing more.
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc::detail {

/// Every boundary of the map's Free cells as a closed ring in world coordinates (m): the
/// midpoint of every cell edge between a Free cell and one that is not, in order along the
/// boundary (the vertices of the marching-squares contour of the Free mask, and one point per
/// edge also along straight runs, so that walls can be fitted to them). Oriented with the free
/// space on the left (a region's outer boundary counter-clockwise, its holes clockwise). Free
/// cells are 4-connected: cells touching only at a corner are separate regions, with separate
/// rings. Unknown and Occupied cells, and the outside of the grid, are not free. Free regions
/// of fewer than `min_region_cells` cells are left out.
std::vector<Polygon> free_outline(const OccupancyMap& map, int min_region_cells);

}  // namespace gridloc::detail
