#include "gridloc/engine/disambiguation/geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "boost_geometry.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

namespace bgw = boost_geometry;
namespace bg = boost::geometry;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kCollinear = 1e-12;  ///< |sin| below which three points count as collinear

/// What the segment tests need of an area: its edges (area on the left) and a Boost polygon
/// for closed point-in-area tests.
struct AreaIndex {
  std::vector<Segment> edges;
  bgw::BoostPolygon polygon;
};

AreaIndex index_area(const Area& area) {
  return {area_edges(area), bgw::to_boost(area)};
}

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

/// The side of p from the line a-b: +1 left, -1 right, 0 on it (within kCollinear).
int side(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const double value = cross(b - a, p - a);
  const double tolerance = kCollinear * (b - a).norm() * (p - a).norm();
  return value > tolerance ? 1 : (value < -tolerance ? -1 : 0);
}

bool boxes_apart(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Segment& edge) {
  return std::max(a.x(), b.x()) < std::min(edge.a.x(), edge.b.x()) ||
         std::min(a.x(), b.x()) > std::max(edge.a.x(), edge.b.x()) ||
         std::max(a.y(), b.y()) < std::min(edge.a.y(), edge.b.y()) ||
         std::min(a.y(), b.y()) > std::max(edge.a.y(), edge.b.y());
}

bool crosses_properly(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Segment& edge) {
  return side(a, b, edge.a) * side(a, b, edge.b) < 0 &&
         side(edge.a, edge.b, a) * side(edge.a, edge.b, b) < 0;
}

bool covers_point(const AreaIndex& index, const Eigen::Vector2d& p) {
  return bg::covered_by(bgw::to_boost(p), index.polygon);
}

/// Splits a-b at every area vertex on it (parameters in [0, 1], sorted); false when an edge
/// crosses a-b properly.
bool split_at_vertices(const AreaIndex& index, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       std::vector<double>& parameters) {
  const Eigen::Vector2d direction = b - a;
  const double length2 = direction.squaredNorm();
  for (const Segment& edge : index.edges) {  // each vertex is the start of one edge
    if (boxes_apart(a, b, edge)) continue;
    if (crosses_properly(a, b, edge)) return false;
    if (side(a, b, edge.a) != 0) continue;
    const double t = (edge.a - a).dot(direction) / length2;
    if (t > 0.0 && t < 1.0) parameters.push_back(t);
  }
  std::sort(parameters.begin(), parameters.end());
  return true;
}

/// The closed segment lies in the closed area: no proper crossing, and between consecutive
/// vertices on it (or touching points) each sub-segment's midpoint is in the area.
bool segment_in(const AreaIndex& index, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if (a == b) return covers_point(index, a);
  std::vector<double> parameters{0.0, 1.0};
  if (!split_at_vertices(index, a, b, parameters)) return false;
  for (std::size_t i = 0; i + 1 < parameters.size(); ++i) {
    if (parameters[i + 1] <= parameters[i]) continue;
    const double middle = 0.5 * (parameters[i] + parameters[i + 1]);
    if (!covers_point(index, a + middle * (b - a))) return false;
  }
  return true;
}

void check_area(const Area& area, const char* who) {
  if (area.outer.size() < 3) {
    throw Error(std::string(who) + ": the area's outer ring has fewer than 3 vertices");
  }
}

/// The ring's reflex vertices w.r.t. the area (the area on the left of the ring's edges):
/// those where the boundary turns right — the outer ring's corners over 180°, the holes'
/// convex corners.
void append_reflex_vertices(const Polygon& ring, std::vector<Eigen::Vector2d>& nodes) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& before = ring[(i + ring.size() - 1) % ring.size()];
    const Eigen::Vector2d& after = ring[(i + 1) % ring.size()];
    if (side(before, ring[i], after) < 0) nodes.push_back(ring[i]);
  }
}

/// The unsettled node nearest the source (-1 when every reached node is settled).
int nearest_unsettled(const std::vector<double>& distance, const std::vector<bool>& settled) {
  int nearest = -1;
  for (std::size_t i = 0; i < distance.size(); ++i) {
    if (settled[i] || distance[i] == kInfinity) continue;
    if (nearest < 0 || distance[i] < distance[nearest]) nearest = static_cast<int>(i);
  }
  return nearest;
}

/// Dijkstra (array-based, iterative) on the visibility graph of the source and the nodes; an
/// edge is tested (segment_in) only when it would shorten the path it reaches.
void shortest_distances(const AreaIndex& index, const Eigen::Vector2d& source,
                        const std::vector<Eigen::Vector2d>& nodes, std::vector<double>& distance,
                        std::vector<int>& previous) {
  distance.assign(nodes.size(), kInfinity);
  previous.assign(nodes.size(), -1);
  for (std::size_t v = 0; v < nodes.size(); ++v) {
    if (segment_in(index, source, nodes[v])) distance[v] = (nodes[v] - source).norm();
  }
  std::vector<bool> settled(nodes.size(), false);
  for (int u = nearest_unsettled(distance, settled); u >= 0;
       u = nearest_unsettled(distance, settled)) {
    settled[u] = true;
    for (std::size_t v = 0; v < nodes.size(); ++v) {
      const double through_u = distance[u] + (nodes[v] - nodes[u]).norm();
      if (settled[v] || through_u >= distance[v]) continue;
      if (!segment_in(index, nodes[u], nodes[v])) continue;
      distance[v] = through_u;
      previous[v] = u;
    }
  }
}

std::string point_text(const Eigen::Vector2d& p) {
  return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
}

}  // namespace

struct GeodesicDistance::Index {
  AreaIndex area;
};

bool segment_inside(const Area& area, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  check_area(area, "segment_inside");
  return segment_in(index_area(area), a, b);
}

GeodesicDistance::GeodesicDistance(const Area& area, const Eigen::Vector2d& source)
    : source_(source) {
  check_area(area, "GeodesicDistance");
  area_ = bgw::to_area(bgw::to_boost(area));  // oriented: outer ccw, holes cw
  index_ = std::make_shared<const Index>(Index{index_area(area_)});
  if (!covers_point(index_->area, source)) {
    throw Error("GeodesicDistance: the source " + point_text(source) + " lies outside the area");
  }
  append_reflex_vertices(area_.outer, nodes_);
  for (const Polygon& hole : area_.holes) append_reflex_vertices(hole, nodes_);
  shortest_distances(index_->area, source_, nodes_, distance_, previous_);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (distance_[i] < kInfinity) order_.push_back(static_cast<int>(i));
  }
  std::sort(order_.begin(), order_.end(), [&](int i, int j) {
    return distance_[i] < distance_[j] || (distance_[i] == distance_[j] && i < j);
  });
}

std::pair<double, int> GeodesicDistance::last_leg(const Eigen::Vector2d& target) const {
  if (!covers_point(index_->area, target)) return {kInfinity, -2};
  std::pair<double, int> best{kInfinity, -2};
  const double direct = (target - source_).norm();
  if (segment_in(index_->area, source_, target)) best = {direct, -1};
  for (const int node : order_) {  // increasing distance: stop once none can be shorter
    if (distance_[node] >= best.first) break;
    const double via = distance_[node] + (target - nodes_[node]).norm();
    if (via >= best.first) continue;  // cheap bound before the visibility test
    if (segment_in(index_->area, nodes_[node], target)) best = {via, node};
  }
  return best;
}

double GeodesicDistance::distance_to(const Eigen::Vector2d& target) const {
  return last_leg(target).first;
}

std::vector<Eigen::Vector2d> GeodesicDistance::path_to(const Eigen::Vector2d& target) const {
  const int last = last_leg(target).second;
  if (last == -2) return {};
  std::vector<Eigen::Vector2d> path{target};
  for (int node = last; node >= 0; node = previous_[node]) path.push_back(nodes_[node]);
  path.push_back(source_);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace gridloc
