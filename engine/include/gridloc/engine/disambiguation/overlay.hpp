#pragma once
/// The overlay arrangement of seed 002 §IV (Figs 3-5): the map's free space seen from each
/// hypothesis's start frame, their intersection, and OI, the component of that intersection
/// that holds the robot: the ground known to exist whichever hypothesis is true.
#include <Eigen/Core>
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

struct Overlay {
  std::vector<Pose2> hypotheses;  ///< the robot's start pose in the world under each
  std::vector<Area> maps;         ///< the free space in the start frame under each hypothesis
  Region intersection;            ///< the intersection of all maps (every component)
  Area oi;                        ///< the component of `intersection` holding `anchor`
  /// OI's boundary split into pieces, each either internal (seed 002 Fig. 5: beyond it, some
  /// hypothesis has free space) or on the outer silhouette (beyond it no map is free). Each
  /// OI edge is split wherever an edge of any map crosses or touches it; a piece keeps its
  /// edge's direction (OI on its left) and is classified by a probe 1e-7 x scale beyond its
  /// midpoint along the outward normal (scale: the larger side of free_world's bounding box,
  /// at least 1), covered by some map or not; pieces under 1e-9 long are dropped.
  std::vector<PlanarSegment> internal_edges;
  std::vector<PlanarSegment> silhouette_edges;
};

/// Builds the overlay; `anchor` (start frame) is a point of the closed OI — the start
/// (origin) or where the robot stands now. Throws gridloc::Error when `hypotheses` is empty
/// or holds a non-finite pose, free_world is not a valid polygon with holes (Boost.Geometry's
/// is_valid, the reason in the message), or no component of the intersection holds the anchor
/// (the message names it); touching components that both hold it: the first is OI.
Overlay make_overlay(const Area& free_world, const std::vector<Pose2>& hypotheses,
                     const Eigen::Vector2d& anchor = Eigen::Vector2d::Zero());

/// Whether p lies in the closed area (inside or on its boundary).
bool covers(const Area& area, const Eigen::Vector2d& p);

/// Whether p lies in some area of the region (closed).
bool covers(const Region& region, const Eigen::Vector2d& p);

/// The total size of a region (square units).
double region_size(const Region& region);

}  // namespace gridloc
