#pragma once
/// Polygon maps: an environment as an outer boundary and obstacle polygons in metres (the
/// polygonal world of seed 000's visibility sectors), and their rasterization into an
/// occupancy map, so one file feeds both the sector estimator and the correlation engine.
///
/// File format (YAML; `#` comments):
///
///     # gridloc polygon map
///     resolution: 0.05          # optional: cell size of the rasterized map (m), default 0.05
///     boundary:                 # the outer wall, a closed ring: the last vertex repeats the first
///       [[0, 0], [6, 0], [6, 4.5], [0, 4.5], [0, 0]]
///     obstacles:                # optional: closed rings inside the boundary
///       - [[2.6, 2.0], [3.4, 2.0], [3.4, 2.8], [2.6, 2.8], [2.6, 2.0]]
///
/// Vertices are [x, y] in the world frame (m). Rings may be given in either orientation;
/// they are stored counter-clockwise (boundary) and clockwise (obstacles), so the free space
/// lies to the left of every edge. A ring must be closed, simple (no edge crosses another, no
/// repeated vertex), of non-zero area; obstacles must lie strictly inside the boundary and
/// apart from each other.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/limits.hpp"

namespace gridloc {

using Polygon = std::vector<Eigen::Vector2d>;  ///< vertices in order, not repeated at the end

struct PolygonMap {
  Polygon boundary;                ///< counter-clockwise
  std::vector<Polygon> obstacles;  ///< each clockwise
  double resolution = 0.05;        ///< of rasterize_polygon_map() by default (m)
};

/// Twice the signed area (positive counter-clockwise).
double signed_area2(const Polygon& polygon);

/// Whether p lies strictly inside the polygon (even-odd rule; points on an edge are not).
bool inside(const Polygon& polygon, const Eigen::Vector2d& p);

/// Checks the rules of the format and orients the rings; throws gridloc::Error naming the ring
/// ("boundary", "obstacle 2") and the fault: fewer than 3 vertices, a non-finite vertex, zero
/// area, a repeated vertex, crossing edges, an obstacle outside the boundary or touching
/// another ring. First, the vertices of all rings together must not exceed
/// limits.max_vertices (the checks are quadratic in them), nor any coordinate
/// limits.max_coordinate_m.
PolygonMap make_polygon_map(Polygon boundary, std::vector<Polygon> obstacles,
                            double resolution = 0.05, const ResourceLimits& limits = {});

/// Reads a polygon map file; gridloc::Error naming the file for a file check_input_file()
/// refuses (missing, a directory, over max_file_mb), YAML that is not a polygon map, more
/// vertices than limits.max_vertices (checked before the rings are read), a ring that is not
/// closed (its last vertex must repeat the first), and every fault make_polygon_map() finds.
PolygonMap load_polygon_map(const std::string& path, const ResourceLimits& limits = {});

/// Writes `map` as a polygon map file that load_polygon_map() reads back to the same rings
/// and resolution (each number as the shortest text that reads back exactly, each ring
/// closed by repeating its first vertex).
/// `comment` (may be empty) goes first, each of its lines as a `#` comment. Writes the rings
/// as they are (load_polygon_map checks them); throws gridloc::Error naming the file when it
/// cannot be written.
void save_polygon_map(const PolygonMap& map, const std::string& path,
                      const std::string& comment = {});

/// Whether a YAML file is a polygon map (has a `boundary` key) rather than a map_server map;
/// false for a file that cannot be read within `limits` (the map loader then says why).
bool is_polygon_map_file(const std::string& path, const ResourceLimits& limits = {});

/// Every edge of every ring, (a, b) with the free space on the left.
std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> polygon_edges(const PolygonMap& map);

/// The occupancy map of a polygon map at `resolution` (m; 0 = the map's own): cells an edge
/// passes through are Occupied, so every wall is a closed contour; other cells inside the
/// boundary and outside every obstacle are Free, obstacle interiors Occupied, and the band of
/// `margin_m` around the boundary Unknown. Throws gridloc::Error for a bad resolution or margin,
/// or a grid over limits.max_cells (its size checked as doubles before any cast).
OccupancyMap rasterize_polygon_map(const PolygonMap& map, double resolution = 0.0,
                                   double margin_m = 0.5, const ResourceLimits& limits = {});

}  // namespace gridloc
