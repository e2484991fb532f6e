#pragma once
/// The map side of team localization (seed 003 ch. III): the corners and walls a robot's
/// detected features can be placed on. Polygon maps give them exactly (their vertices and
/// edges); occupancy maps give them from the free space's outline, simplified to straight
/// walls.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc {

/// A wall of the map, from a to b with the free space on its left (the orientation of
/// polygon_edges(): a robot's scan, ordered counter-clockwise, runs along a wall the same way).
using MapWall = Segment2;

/// A vertex of the map where two walls meet: `in` (index into MapFeatures::walls) arrives at
/// `point`, `out` leaves it. Concave: the free space turns left there (a room's inside corner,
/// interior angle on the free side < 180 deg); convex: right (a protruding corner, > 180 deg).
struct MapCorner {
  Eigen::Vector2d point;
  int in = -1, out = -1;
  /// Interior angle on the free side (rad), in (0, 2 pi): pi minus the signed turn (left
  /// positive) from the arriving wall's direction to the leaving wall's.
  double free_angle = 0.0;
  bool convex() const;  ///< free_angle > pi
};

/// The walls ring by ring, each ring's walls in order (wall k from its vertex k to k + 1), and
/// the corners ring by ring in vertex order.
struct MapFeatures {
  std::vector<MapWall> walls;
  std::vector<MapCorner> corners;  ///< every vertex whose walls turn by at least the options'
                                   ///< min_turn (straighter vertices are no corner; their walls
                                   ///< stay separate walls)
  /// True for a polygon map's own corners and walls; false when they were inferred from an
  /// occupancy grid's outline, which can miss or move a corner (a round pillar, clutter): a
  /// feature placed on them may then find a wrong place and miss the true one.
  bool exact = true;
};

struct MapFeatureOptions {
  /// A vertex whose walls turn by less than this (rad) is no corner (a wall's kink).
  double min_turn = 0.261799387799;  ///< 15 deg
  /// Occupancy maps: outline simplification tolerance (m; Douglas-Peucker), and the shortest
  /// wall kept (m): shorter pieces of outline (a grid's stair steps) are merged into their
  /// neighbours. A coarse grid raises them to at least 1.5 and 3 cells (the outline zigzags by
  /// up to a cell along a slanted wall; a rasterized wall's cut corners run up to 3 cells).
  double simplify_m = 0.05;
  double min_wall_m = 0.10;
};

/// Checks the options: every field positive and finite, min_turn in (0, pi); throws
/// gridloc::Error naming the field.
void validate(const MapFeatureOptions& options);

/// The walls (one per edge, in polygon_edges() order: the boundary, then each obstacle; free
/// space on the left) and corners of a polygon map, exactly. Throws gridloc::Error for options
/// validate() refuses or a ring of fewer than 3 vertices.
MapFeatures polygon_features(const PolygonMap& map, const MapFeatureOptions& options = {});

/// The walls and corners of an occupancy map (world frame, m): the outline of its free space
/// (each 4-connected free region's outer and inner boundaries: the marching-squares contour
/// between Free cells and the rest, Unknown counting as not free), broken into straight
/// pieces by Douglas-Peucker at simplify_m, pieces and walls shorter than min_wall_m merged
/// away, each wall the least-squares line through its piece of outline and each vertex the
/// intersection of its two walls' lines; the same orientation rule as polygons (free space on
/// the left). Free regions of fewer than 9 cells, and rings that merge away to fewer than 3
/// walls, are left out. Throws
/// gridloc::Error for options validate() refuses and for a map without free cells
/// ("occupancy map has no free cells").
MapFeatures occupancy_features(const OccupancyMap& map, const MapFeatureOptions& options = {});

}  // namespace gridloc
