#pragma once
/// The map side of team localization (seed 003 ch. III): the corners and walls a robot's
/// detected features can be placed on. Polygon maps give them exactly (their vertices and
/// edges); occupancy maps give them from the free space's outline, simplified to straight
/// walls.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc {

/// A wall of the map, from a to b with the free space on its left (the orientation of
/// polygon_edges(): a robot's scan, ordered counter-clockwise, runs along a wall the same way).
struct MapWall {
  Eigen::Vector2d a, b;
};

/// A vertex of the map where two walls meet: `in` (index into MapFeatures::walls) arrives at
/// `point`, `out` leaves it. Concave: the free space turns left there (a room's inside corner,
/// interior angle on the free side < 180 deg); convex: right (a protruding corner, > 180 deg).
struct MapCorner {
  Eigen::Vector2d point;
  int in = -1, out = -1;
  double free_angle = 0.0;  ///< interior angle on the free side (rad), in (0, 2 pi)
  bool convex() const;      ///< free_angle > pi
};

struct MapFeatures {
  std::vector<MapWall> walls;
  std::vector<MapCorner> corners;  ///< every vertex whose walls turn by more than the options'
                                   ///< min_turn (straighter vertices are no corner)
};

struct MapFeatureOptions {
  /// A vertex whose walls turn by less than this (rad) is no corner (a wall's kink).
  double min_turn = 0.261799387799;  ///< 15 deg
  /// Occupancy maps: outline simplification tolerance (m; Douglas-Peucker), and the shortest
  /// wall kept (m): shorter pieces of outline (a grid's stair steps) are merged into their
  /// neighbours.
  double simplify_m = 0.05;
  double min_wall_m = 0.10;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const MapFeatureOptions& options);

/// The walls (one per edge, free space on the left) and corners of a polygon map, exactly.
MapFeatures polygon_features(const PolygonMap& map, const MapFeatureOptions& options = {});

/// The walls and corners of an occupancy map: the outline of its free space (each connected
/// free region's outer and inner boundaries), simplified to straight walls; the same
/// orientation rule as polygons (free space on the left). Throws gridloc::Error for a map
/// without free cells.
MapFeatures occupancy_features(const OccupancyMap& map, const MapFeatureOptions& options = {});

}  // namespace gridloc
