#pragma once
/// Random office environments for seed 002's protocol (§V: "twenty simulated office
/// environments of average number of vertices approximately 400", grid cells of 100 px). An
/// office is a simple rectilinear polygon without holes (§III) in grid-cell units (1 unit = 1
/// cell, so the paper's ranges 500, 200, 90 px are 5, 2, 0.9 units): a tree of corridors with
/// rows of rooms along them, each room opening onto its corridor through one door, most rooms
/// repeating the previous room's shape so that many start locations look alike.
///
/// Construction (on the integer grid): corridors are straight strips, each branching off an
/// earlier one at a right angle (a tree, so no cycle and no hole); a room is a rectangle, or an
/// L (a far corner cut away), one wall cell away from its corridor, joined to it by a door strip
/// through that wall. Every new piece keeps a gap of at least one cell from all earlier cells
/// except where it joins its corridor. Pieces are added one at a time until the traced
/// boundary has at least target_vertices vertices.
#include <cstdint>

#include "gridloc/grids/polygon_map.hpp"

namespace gridloc {

/// What random_office() draws from; sizes in grid cells. The defaults give offices of 400 to
/// 406 vertices over seeds 1..20 (mean 402.2), 50 to 140 cells across.
struct OfficeOptions {
  int target_vertices = 400;  ///< pieces are added until the boundary has at least this many
  int min_room_width = 3;     ///< room extent along its corridor (cells)
  int max_room_width = 6;
  int min_room_depth = 3;  ///< room extent away from its corridor (cells)
  int max_room_depth = 5;
  int corridor_width = 1;            ///< cells
  int door_width = 1;                ///< cells along the corridor; at most min_room_width
  int min_corridor_length = 12;      ///< a corridor branch's length (cells)
  int max_corridor_length = 30;      ///< also the first corridor's length
  double repeat_probability = 0.8;   ///< a room repeats the previous room's shape (and door)
  double notch_probability = 0.3;    ///< a newly drawn room shape is an L rather than a rectangle
  double branch_probability = 0.05;  ///< each piece tried is a corridor branch rather than a room
  double resolution = 0.05;          ///< the PolygonMap's rasterization cell (map units)
  int max_attempts = 20000;          ///< pieces tried before giving up
};

/// A random office for `seed` (the same map for the same seed and options on every platform):
/// a counter-clockwise boundary with integer vertex coordinates (cells, the lowest cell corner
/// at the origin), no collinear vertices, no obstacles, checked by make_polygon_map(). Throws
/// gridloc::Error for bad options (a size < 1, min > max, a probability outside [0, 1], a door
/// wider than the narrowest room, a corridor wider than max_corridor_length, target_vertices
/// outside [4, ResourceLimits{}.max_vertices]) or when max_attempts pieces tried do not reach
/// the target (the office has grown into a corner: raise branch_probability or max_attempts).
PolygonMap random_office(std::uint64_t seed, const OfficeOptions& options = {});

}  // namespace gridloc
