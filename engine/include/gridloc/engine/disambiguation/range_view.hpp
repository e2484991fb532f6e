#pragma once
/// Range-limited visibility (seed 002 §III-B): what a perfect range sensor of range d sees
/// from a point of an area: the pieces of the walls with an unobstructed line of sight no
/// longer than d, in counter-clockwise order. Two places look the same when their views are
/// congruent under translation with the same orientation (seed 002 §IV-A's equivalence).
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"

namespace gridloc {

/// One visible piece of a wall: the points q of one edge with the segment viewpoint-q inside
/// the (closed) area and |q - viewpoint| <= range.
struct ViewPiece {
  /// In the viewer's frame: relative to the viewpoint, axes turned by -heading. As seen from
  /// the viewpoint, a comes before b counter-clockwise.
  PlanarSegment segment;
  bool a_is_vertex = false;  ///< a is a vertex of the area (not a cut by occlusion or range)
  bool b_is_vertex = false;
};

/// The visibility data W of seed 002 §III: every visible wall piece, split where it crosses
/// the viewer's -x axis, sorted counter-clockwise by the angle of `a` in [-pi, pi). Pieces
/// shorter than 1e-9 are left out. Empty when no wall lies within range.
struct RangeView {
  std::vector<ViewPiece> pieces;
};

constexpr double kUnlimitedRange = std::numeric_limits<double>::infinity();

/// The view from `viewpoint` (world frame, inside the area) of a robot heading `heading`
/// (rad) with a sensor of range `range` (> 0; kUnlimitedRange for seed 002's d*).
RangeView range_view(const Area& area, const Eigen::Vector2d& viewpoint, double heading,
                     double range);

/// Whether two views are the same: as many pieces, each end within `tolerance` of the other
/// view's and of the same kind (vertex or cut).
bool same_view(const RangeView& first, const RangeView& second, double tolerance = 1e-6);

/// How many area vertices the view holds (ends flagged as vertices, each counted once).
int visible_vertex_count(const RangeView& view);

/// The visibility polygon of `viewpoint` (world frame) clipped to the disk of `range`, the
/// disk's arcs drawn with chords of at most 2 pi / arc_segments each: the points of the area
/// that the viewpoint sees within range. Counter-clockwise, world frame.
Polygon visibility_polygon(const Area& area, const Eigen::Vector2d& viewpoint, double range,
                           int arc_segments = 64);

/// Seed 002 §IV-D step 6: the useful region U of an overlay intersection `oi` — the union of
/// the weak visibility polygons (inside oi) of its internal edges, each clipped to the
/// rectangle of width `range` along its edge on oi's side (unclipped for kUnlimitedRange).
/// A weak visibility polygon is the union of the visibility polygons of `samples_per_edge`
/// points spread along the edge, pulled 1e-7 into oi (an inner approximation).
Region useful_region(const Area& oi, const std::vector<PlanarSegment>& internal_edges, double range,
                     int samples_per_edge = 16);

}  // namespace gridloc
