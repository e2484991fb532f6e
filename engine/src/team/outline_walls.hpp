#pragma once
// Straight walls from a traced outline: Douglas-Peucker breaks the ring into pieces, pieces
// too short to be walls are dropped, and each wall is a line fitted to its piece's points.
// Internal to the engine (map_features.cpp).
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc::detail {

/// The vertices of the walls of a densely sampled closed ring (m; free_outline()'s):
/// 1. Douglas-Peucker at `tolerance_m` breaks the ring into pieces (every point lies within
///    the tolerance of its piece's chord; the two starting anchors, about the ring's two
///    farthest-apart points, stay only where the ring bends by more than the tolerance);
/// 2. pieces whose chord is shorter than `min_wall_m` are dropped (a grid's steps and cut
///    corners), so their neighbours meet;
/// 3. each remaining piece's wall is the total-least-squares line through its points (its
///    two end points left out when it has at least 4: they may lie on the next wall), and
///    vertex k is where walls k - 1 and k meet: their lines' intersection, or the middle of
///    the gap between their pieces when the lines are near parallel or meet behind them;
/// 4. while a wall is shorter than `min_wall_m` between its vertices (or runs backwards), the
///    shortest is dropped and its neighbours meet.
/// Vertex k starts wall k, which runs the ring's way. Empty when fewer than 3 walls remain
/// (a speck).
Polygon fit_walls(const Polygon& dense, double tolerance_m, double min_wall_m);

}  // namespace gridloc::detail
