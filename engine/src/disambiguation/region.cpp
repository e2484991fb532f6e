#include "gridloc/engine/disambiguation/region.hpp"

#include <cmath>

namespace gridloc {

Area free_area(const PolygonMap& map) {
  return Area{map.boundary, map.obstacles};
}

Eigen::Vector2d to_world(const Pose2& start, const Eigen::Vector2d& local) {
  const double c = std::cos(start.theta), s = std::sin(start.theta);
  return {c * local.x() - s * local.y() + start.x, s * local.x() + c * local.y() + start.y};
}

Eigen::Vector2d to_start_frame(const Pose2& start, const Eigen::Vector2d& world) {
  const double c = std::cos(start.theta), s = std::sin(start.theta);
  const double dx = world.x() - start.x, dy = world.y() - start.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}

namespace {

Polygon ring_to_start_frame(const Pose2& start, const Polygon& ring) {
  Polygon moved;
  moved.reserve(ring.size());
  for (const Eigen::Vector2d& vertex : ring) moved.push_back(to_start_frame(start, vertex));
  return moved;
}

void append_ring_edges(const Polygon& ring, std::vector<PlanarSegment>& edges) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
  }
}

}  // namespace

Area to_start_frame(const Pose2& start, const Area& area) {
  Area moved{ring_to_start_frame(start, area.outer), {}};
  for (const Polygon& hole : area.holes) moved.holes.push_back(ring_to_start_frame(start, hole));
  return moved;
}

std::vector<PlanarSegment> area_edges(const Area& area) {
  std::vector<PlanarSegment> edges;
  append_ring_edges(area.outer, edges);
  for (const Polygon& hole : area.holes) append_ring_edges(hole, edges);
  return edges;
}

double area_size(const Area& area) {
  double twice = signed_area2(area.outer);
  for (const Polygon& hole : area.holes) twice += signed_area2(hole);  // holes are clockwise
  return 0.5 * twice;
}

}  // namespace gridloc
