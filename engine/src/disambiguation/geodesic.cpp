#include "gridloc/engine/disambiguation/geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "boost_geometry.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"

namespace gridloc {

namespace {

namespace bgw = boost_geometry;
namespace bg = boost::geometry;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kCollinear = 1e-12;  ///< |sin| below which three points count as collinear

/// What the segment tests need of an area: its edges (area on the left), each edge's
/// neighbours along its ring, whether its start is a reflex vertex, and a Boost polygon for
/// closed point-in-area tests.
struct AreaIndex {
  std::vector<PlanarSegment> edges;
  std::vector<std::size_t> next_edge, previous_edge;
  std::vector<bool> starts_reflex;
  bgw::BoostPolygon polygon;
};

/// The side of p from the line a-b: +1 left, -1 right, 0 on it (within kCollinear).
int side(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const double value = cross(b - a, p - a);
  const double tolerance = kCollinear * (b - a).norm() * (p - a).norm();
  return value > tolerance ? 1 : (value < -tolerance ? -1 : 0);
}

/// Indexes the area; its reflex vertices are those where the boundary turns right (the area
/// on the left of every edge): the outer ring's corners over 180°, the holes' convex corners.
AreaIndex index_area(const Area& area) {
  AreaIndex index{area_edges(area), {}, {}, {}, bgw::to_boost(area)};
  std::size_t first = 0;  // area_edges: the outer ring's edges, then each hole's
  auto link_ring = [&](std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
      index.next_edge.push_back(first + (i + 1) % size);
      index.previous_edge.push_back(first + (i + size - 1) % size);
    }
    first += size;
  };
  link_ring(area.outer.size());
  for (const Polygon& hole : area.holes) link_ring(hole.size());
  for (std::size_t e = 0; e < index.edges.size(); ++e) {
    const PlanarSegment& edge = index.edges[e];
    index.starts_reflex.push_back(side(index.edges[index.previous_edge[e]].a, edge.a, edge.b) < 0);
  }
  return index;
}

bool boxes_apart(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const PlanarSegment& edge) {
  return std::max(a.x(), b.x()) < std::min(edge.a.x(), edge.b.x()) ||
         std::min(a.x(), b.x()) > std::max(edge.a.x(), edge.b.x()) ||
         std::max(a.y(), b.y()) < std::min(edge.a.y(), edge.b.y()) ||
         std::min(a.y(), b.y()) > std::max(edge.a.y(), edge.b.y());
}

bool crosses_properly(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      const PlanarSegment& edge) {
  return side(a, b, edge.a) * side(a, b, edge.b) < 0 &&
         side(edge.a, edge.b, a) * side(edge.a, edge.b, b) < 0;
}

bool covers_point(const AreaIndex& index, const Eigen::Vector2d& p) {
  return bg::covered_by(bgw::to_boost(p), index.polygon);
}

/// A point where a segment meets the area's boundary: at parameter t along the segment, the
/// start of edge `edge` (-1: an end of the segment that is no vertex).
struct Split {
  double t;
  int edge;
  bool operator<(const Split& other) const { return t < other.t; }
};

/// Splits a-b at every area vertex on it (sorted, with both ends); false when an edge crosses
/// a-b properly, or when `avoid_reflex` and a reflex vertex lies strictly between a and b.
bool split_at_vertices(const AreaIndex& index, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       bool avoid_reflex, std::vector<Split>& splits) {
  const Eigen::Vector2d direction = b - a;
  const double length2 = direction.squaredNorm();
  splits = {{0.0, -1}, {1.0, -1}};
  for (std::size_t e = 0; e < index.edges.size(); ++e) {  // each vertex starts one edge
    const PlanarSegment& edge = index.edges[e];
    if (boxes_apart(a, b, edge)) continue;
    if (crosses_properly(a, b, edge)) return false;
    if (side(a, b, edge.a) != 0) continue;
    const bool at_end = edge.a == a || edge.a == b;
    const double t =
        edge.a == a ? 0.0 : (edge.a == b ? 1.0 : (edge.a - a).dot(direction) / length2);
    if (t < 0.0 || t > 1.0) continue;
    if (avoid_reflex && !at_end && index.starts_reflex[e]) return false;
    splits.push_back({t, static_cast<int>(e)});
  }
  std::stable_sort(splits.begin(), splits.end());
  return true;
}

/// Whether the piece between two splits is an edge of the area (a wall: in the closed area).
bool along_wall(const AreaIndex& index, const Split& from, const Split& to) {
  if (from.edge < 0 || to.edge < 0) return false;
  const auto i = static_cast<std::size_t>(from.edge), j = static_cast<std::size_t>(to.edge);
  return index.next_edge[i] == j || index.next_edge[j] == i;
}

/// The closed segment lies in the closed area: no proper crossing, and between consecutive
/// vertices on it (or touching points) each sub-segment's midpoint is in the area. With
/// `avoid_reflex`, also false when it passes through a reflex vertex (a path link then
/// goes through that vertex instead, as long).
bool segment_in(const AreaIndex& index, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                bool avoid_reflex = false) {
  if (a == b) return covers_point(index, a);
  thread_local std::vector<Split> splits;  // reused: no allocation per call
  if (!split_at_vertices(index, a, b, avoid_reflex, splits)) return false;
  for (std::size_t i = 0; i + 1 < splits.size(); ++i) {
    if (splits[i + 1].t <= splits[i].t || along_wall(index, splits[i], splits[i + 1])) continue;
    const double middle = 0.5 * (splits[i].t + splits[i + 1].t);
    if (!covers_point(index, a + middle * (b - a))) return false;
  }
  return true;
}

void check_area(const Area& area, const char* who) {
  if (area.outer.size() < 3) {
    throw Error(std::string(who) + ": the area's outer ring has fewer than 3 vertices");
  }
}

/// A reflex vertex with its two neighbours along the boundary.
struct Node {
  Eigen::Vector2d at, before, after;
};

/// The area's reflex vertices (seed 002's distance_OI bends only there).
std::vector<Node> reflex_nodes(const AreaIndex& index) {
  std::vector<Node> nodes;
  for (std::size_t e = 0; e < index.edges.size(); ++e) {
    if (!index.starts_reflex[e]) continue;
    nodes.push_back({index.edges[e].a, index.edges[index.previous_edge[e]].a, index.edges[e].b});
  }
  return nodes;
}

/// Whether the line from p through the node leaves both its boundary edges on one side: a
/// shortest path bends at a reflex vertex only so, wrapping around it (a taut string).
bool tangent(const Node& node, const Eigen::Vector2d& p) {
  return side(p, node.at, node.before) * side(p, node.at, node.after) >= 0;
}

/// Whether a path may go straight from node u to node v, bending at both.
bool useful_link(const AreaIndex& index, const Node& u, const Node& v) {
  return tangent(u, v.at) && tangent(v, u.at) && segment_in(index, u.at, v.at, true);
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

/// Dijkstra (array-based, iterative) on the visibility graph of the source and the nodes,
/// keeping links tangent at the nodes; a link is tested (segment_in) only when it would
/// shorten the path it reaches.
void shortest_distances(const AreaIndex& index, const Eigen::Vector2d& source,
                        const std::vector<Node>& nodes, std::vector<double>& distance,
                        std::vector<int>& previous) {
  distance.assign(nodes.size(), kInfinity);
  previous.assign(nodes.size(), -1);
  for (std::size_t v = 0; v < nodes.size(); ++v) {
    if (tangent(nodes[v], source) && segment_in(index, source, nodes[v].at, true)) {
      distance[v] = (nodes[v].at - source).norm();
    }
  }
  std::vector<bool> settled(nodes.size(), false);
  for (int u = nearest_unsettled(distance, settled); u >= 0;
       u = nearest_unsettled(distance, settled)) {
    settled[u] = true;
    for (std::size_t v = 0; v < nodes.size(); ++v) {
      const double through_u = distance[u] + (nodes[v].at - nodes[u].at).norm();
      if (settled[v] || through_u >= distance[v]) continue;
      if (!useful_link(index, nodes[u], nodes[v])) continue;
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
  std::vector<Node> nodes;  ///< the reflex vertices, as nodes_, with their neighbours
};

bool segment_inside(const Area& area, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  check_area(area, "segment_inside");
  return segment_in(index_area(area), a, b);
}

GeodesicDistance::GeodesicDistance(const Area& area, const Eigen::Vector2d& source)
    : source_(source) {
  check_area(area, "GeodesicDistance");
  area_ = bgw::to_area(bgw::to_boost(area));  // oriented: outer ccw, holes cw
  Index index{index_area(area_), {}};
  if (!covers_point(index.area, source)) {
    throw Error("GeodesicDistance: the source " + point_text(source) + " lies outside the area");
  }
  index.nodes = reflex_nodes(index.area);
  for (const Node& node : index.nodes) nodes_.push_back(node.at);
  index_ = std::make_shared<const Index>(std::move(index));
  shortest_distances(index_->area, source_, index_->nodes, distance_, previous_);
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
    if (via >= best.first) continue;  // cheap bounds before the visibility test
    if (!tangent(index_->nodes[node], target)) continue;
    if (segment_in(index_->area, nodes_[node], target, true)) best = {via, node};
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
