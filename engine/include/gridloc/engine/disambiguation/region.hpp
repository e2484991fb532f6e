#pragma once
/// Planar regions for minimum-distance localization (seed 002): a polygon with holes (the free
/// space of a polygon map, one component of an overlay intersection), sets of them, and the
/// change of frame between the world and a robot's start frame.
///
/// Frames: a hypothesis is the robot's start pose in the world, h = (x, y, theta). The start
/// frame has its origin at the robot's start and its x axis along the robot's heading; a point
/// r of the start frame lies at world point h * r = R(theta) r + (x, y) under hypothesis h.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc {

/// A polygon with holes: the points inside `outer` and outside every hole (closed: the
/// boundary belongs to it; the robot may move along walls, seed 002 §III).
struct Area {
  Polygon outer;               ///< counter-clockwise, last vertex not repeated
  std::vector<Polygon> holes;  ///< each clockwise, strictly inside outer
};

using Region = std::vector<Area>;  ///< disjoint areas

/// An edge of an area, from a to b.
using PlanarSegment = Segment2;

/// The free space of a polygon map: its boundary with its obstacles as holes.
Area free_area(const PolygonMap& map);

/// The world point of start-frame point `local` under hypothesis `start`: R(theta) local + t.
Eigen::Vector2d to_world(const Pose2& start, const Eigen::Vector2d& local);

/// The start-frame point of world point `world` under hypothesis `start`.
Eigen::Vector2d to_start_frame(const Pose2& start, const Eigen::Vector2d& world);

/// `area` (world) seen in the start frame of hypothesis `start`: every vertex mapped by
/// to_start_frame (orientation is kept: a rigid motion).
Area to_start_frame(const Pose2& start, const Area& area);

/// Every edge of the area, outer ring then holes, with the area on the left.
std::vector<PlanarSegment> area_edges(const Area& area);

/// The area in square units (outer minus holes).
double area_size(const Area& area);

}  // namespace gridloc
