#pragma once
/// Shortest paths inside an area (seed 002's distance_OI): the robot moves inside OI and
/// along its walls; a shortest path bends only at the area's reflex vertices, so distances
/// come from Dijkstra on the visibility graph of those vertices.
#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"

namespace gridloc {

/// Whether the closed segment a-b lies in the closed area (it may run along a wall or touch
/// a vertex, never cross into a hole or out of the outer ring): no edge crosses it properly
/// and, split at every area vertex on it, each piece's midpoint is in the closed area.
/// Collinearity is judged with a relative tolerance of 1e-12 (|sin| of the angle). O(n) for
/// n vertices; throws gridloc::Error when the outer ring has fewer than 3 vertices.
bool segment_inside(const Area& area, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// Distances from one source to any point of an area: built once per source (Dijkstra over
/// the visibility graph of the reflex vertices and the source), then each query tests which
/// reached vertices see the target. Only links a shortest path can use are kept: tangent at
/// their reflex vertices (the path wraps around the corner) and through no other reflex
/// vertex (the path then bends there, as long). A query visits the reached vertices by
/// increasing distance and stops once none can beat the best so far. Copies share the
/// immutable index; const queries may run concurrently.
class GeodesicDistance {
 public:
  /// `source` must lie in the closed area; throws gridloc::Error otherwise.
  GeodesicDistance(const Area& area, const Eigen::Vector2d& source);

  /// The length of the shortest path inside the area from the source to `target`;
  /// +infinity when the target is outside the area.
  double distance_to(const Eigen::Vector2d& target) const;

  /// The shortest path's vertices: the source, the reflex vertices it bends at, the target.
  /// Empty when the target is outside the area.
  std::vector<Eigen::Vector2d> path_to(const Eigen::Vector2d& target) const;

 private:
  struct Index;  ///< the area's edges, vertices and point-in-area structure (in the .cpp)

  /// The shortest length to `target` (inside the area) and the last node before it (-1: the
  /// source sees it directly; -2: unreachable).
  std::pair<double, int> last_leg(const Eigen::Vector2d& target) const;

  Area area_;
  std::shared_ptr<const Index> index_;
  Eigen::Vector2d source_;
  std::vector<Eigen::Vector2d> nodes_;  ///< reflex vertices
  std::vector<double> distance_;        ///< per node, from the source (+inf unreached)
  std::vector<int> previous_;           ///< per node, the node before it (-1: the source)
  std::vector<int> order_;              ///< the reached nodes by increasing distance
};

}  // namespace gridloc
