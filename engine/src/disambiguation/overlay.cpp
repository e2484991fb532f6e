#include "gridloc/engine/disambiguation/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "boost_geometry.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

namespace bgw = boost_geometry;
namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

using EdgeTree = bgi::rtree<std::pair<bgw::Box, std::size_t>, bgi::rstar<16>>;

constexpr double kMinPieceLength = 1e-9;  ///< sub-pieces shorter than this are dropped
constexpr double kProbeOffset = 1e-7;     ///< of the map's scale, the probe beyond an edge

/// One map of the overlay in Boost form, with its envelope (a cheap first test).
struct BoostMap {
  bgw::BoostPolygon polygon;
  bgw::Box envelope;
};

std::string point_text(const Eigen::Vector2d& p) {
  return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
}

void check_hypotheses(const std::vector<Pose2>& hypotheses) {
  if (hypotheses.empty()) throw Error("make_overlay: no hypotheses");
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const Pose2& h = hypotheses[i];
    if (!std::isfinite(h.x) || !std::isfinite(h.y) || !std::isfinite(h.theta)) {
      throw Error("make_overlay: hypothesis " + std::to_string(i) + " is not finite");
    }
  }
}

void check_free_world(const Area& free_world) {
  if (free_world.outer.size() < 3) {
    throw Error("make_overlay: free_world's outer ring has fewer than 3 vertices");
  }
  std::string reason;
  if (!bg::is_valid(bgw::to_boost(free_world), reason)) {
    throw Error("make_overlay: free_world is not a valid polygon with holes: " + reason);
  }
}

/// The map's extent (its bounding box's larger side, at least 1): the probe offset's unit.
double map_scale(const Area& free_world) {
  const bgw::Box box = bg::return_envelope<bgw::Box>(bgw::to_boost(free_world));
  const double width = box.max_corner().x() - box.min_corner().x();
  const double height = box.max_corner().y() - box.min_corner().y();
  return std::max({1.0, width, height});
}

/// `area` moved by `offset`.
Area translated(Area area, const Eigen::Vector2d& offset) {
  for (Eigen::Vector2d& vertex : area.outer) vertex += offset;
  for (Polygon& hole : area.holes) {
    for (Eigen::Vector2d& vertex : hole) vertex += offset;
  }
  return area;
}

/// Hypothesis i's map in the start frame. With the heading of the first hypothesis it is the
/// world map moved by h_0 - h_i, that offset snapped to 2^-20, then seen from h_0: look-alike
/// copies found from different vertices sit a few ulps off a whole offset, and walls that
/// coincide must coincide bit for bit (Boost.Geometry's overlay fails on walls 1e-14 apart).
Area start_frame_map(const Area& free_world, const Pose2& first, const Pose2& hypothesis) {
  if (hypothesis.theta != first.theta) return to_start_frame(hypothesis, free_world);
  const Eigen::Vector2d offset(first.x - hypothesis.x, first.y - hypothesis.y);
  const Eigen::Vector2d snapped = (offset * 0x1.0p20).array().round() * 0x1.0p-20;
  return to_start_frame(first, translated(free_world, snapped));
}

/// seed 002 §IV step 4: each hypothesis's view of the map, centred on its start.
std::vector<BoostMap> start_frame_maps(const Area& free_world, Overlay& overlay) {
  std::vector<BoostMap> maps;
  maps.reserve(overlay.hypotheses.size());
  for (const Pose2& hypothesis : overlay.hypotheses) {
    overlay.maps.push_back(start_frame_map(free_world, overlay.hypotheses.front(), hypothesis));
    bgw::BoostPolygon polygon = bgw::to_boost(overlay.maps.back());
    const bgw::Box envelope = bg::return_envelope<bgw::Box>(polygon);
    maps.push_back({std::move(polygon), envelope});
  }
  return maps;
}

/// seed 002 §IV step 5: the intersection of every map (all components).
bgw::MultiPolygon intersect_all(const std::vector<BoostMap>& maps) {
  bgw::MultiPolygon accumulated{maps.front().polygon};
  for (std::size_t i = 1; i < maps.size() && !accumulated.empty(); ++i) {
    bgw::MultiPolygon next;
    bg::intersection(accumulated, maps[i].polygon, next);
    accumulated = std::move(next);
  }
  bg::correct(accumulated);
  return accumulated;
}

/// The first component covering the anchor (closed); throws when none does.
std::size_t component_holding(const bgw::MultiPolygon& intersection,
                              const Eigen::Vector2d& anchor) {
  const bgw::Point point = bgw::to_boost(anchor);
  for (std::size_t i = 0; i < intersection.size(); ++i) {
    if (bg::covered_by(point, intersection[i])) return i;
  }
  throw Error("make_overlay: no component of the overlay intersection holds the anchor " +
              point_text(anchor));
}

std::vector<PlanarSegment> all_map_edges(const std::vector<Area>& maps) {
  std::vector<PlanarSegment> edges;
  for (const Area& map : maps) {
    const std::vector<PlanarSegment> map_edges = area_edges(map);
    edges.insert(edges.end(), map_edges.begin(), map_edges.end());
  }
  return edges;
}

bgw::Box segment_box(const PlanarSegment& segment) {
  return {{std::min(segment.a.x(), segment.b.x()), std::min(segment.a.y(), segment.b.y())},
          {std::max(segment.a.x(), segment.b.x()), std::max(segment.a.y(), segment.b.y())}};
}

EdgeTree edge_tree(const std::vector<PlanarSegment>& edges) {
  std::vector<std::pair<bgw::Box, std::size_t>> values;
  values.reserve(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) values.emplace_back(segment_box(edges[i]), i);
  return EdgeTree(values.begin(), values.end());  // bulk loading (packing)
}

/// Where along `edge` (parameter 0 at a, 1 at b) the map edges cross or touch it, sorted,
/// with 0 and 1.
std::vector<double> split_parameters(const PlanarSegment& edge,
                                     const std::vector<PlanarSegment>& map_edges,
                                     const EdgeTree& tree) {
  std::vector<double> parameters{0.0, 1.0};
  const Eigen::Vector2d direction = edge.b - edge.a;
  const double length2 = direction.squaredNorm();
  const bgw::BoostSegment edge_segment{bgw::to_boost(edge.a), bgw::to_boost(edge.b)};
  std::vector<bgw::Point> crossings;
  for (auto it = tree.qbegin(bgi::intersects(segment_box(edge))); it != tree.qend(); ++it) {
    const PlanarSegment& other = map_edges[it->second];
    crossings.clear();
    bg::intersection(edge_segment,
                     bgw::BoostSegment{bgw::to_boost(other.a), bgw::to_boost(other.b)}, crossings);
    for (const bgw::Point& p : crossings) {
      const double t = (bgw::to_eigen(p) - edge.a).dot(direction) / length2;
      parameters.push_back(std::clamp(t, 0.0, 1.0));
    }
  }
  std::sort(parameters.begin(), parameters.end());
  return parameters;
}

/// Whether some map covers p (closed), envelopes first.
bool some_map_covers(const std::vector<BoostMap>& maps, const Eigen::Vector2d& p) {
  const bgw::Point point = bgw::to_boost(p);
  return std::any_of(maps.begin(), maps.end(), [&](const BoostMap& map) {
    return bg::covered_by(point, map.envelope) && bg::covered_by(point, map.polygon);
  });
}

/// seed 002 §IV-D, Fig. 5: each piece of OI's boundary is internal when some map has free
/// space just beyond it (a probe offset along the outward normal), else on the silhouette.
void classify_pieces(const PlanarSegment& edge, const std::vector<double>& parameters,
                     const std::vector<BoostMap>& maps, double probe_offset, Overlay& overlay) {
  const Eigen::Vector2d direction = edge.b - edge.a;
  const double length = direction.norm();
  const Eigen::Vector2d outward(direction.y() / length, -direction.x() / length);  // OI on left
  for (std::size_t i = 0; i + 1 < parameters.size(); ++i) {
    if ((parameters[i + 1] - parameters[i]) * length < kMinPieceLength) continue;
    const PlanarSegment piece{edge.a + parameters[i] * direction,
                              edge.a + parameters[i + 1] * direction};
    const Eigen::Vector2d probe = 0.5 * (piece.a + piece.b) + probe_offset * outward;
    (some_map_covers(maps, probe) ? overlay.internal_edges : overlay.silhouette_edges)
        .push_back(piece);
  }
}

void split_oi_boundary(const std::vector<BoostMap>& maps, double probe_offset, Overlay& overlay) {
  const std::vector<PlanarSegment> map_edges = all_map_edges(overlay.maps);
  const EdgeTree tree = edge_tree(map_edges);
  for (const PlanarSegment& edge : area_edges(overlay.oi)) {
    if ((edge.b - edge.a).norm() < kMinPieceLength) continue;
    classify_pieces(edge, split_parameters(edge, map_edges, tree), maps, probe_offset, overlay);
  }
}

}  // namespace

Overlay make_overlay(const Area& free_world, const std::vector<Pose2>& hypotheses,
                     const Eigen::Vector2d& anchor) {
  check_hypotheses(hypotheses);
  check_free_world(free_world);
  Overlay overlay;
  overlay.hypotheses = hypotheses;
  const std::vector<BoostMap> maps = start_frame_maps(free_world, overlay);
  const bgw::MultiPolygon intersection = intersect_all(maps);
  overlay.intersection.reserve(intersection.size());
  for (const bgw::BoostPolygon& component : intersection) {
    overlay.intersection.push_back(bgw::to_area(component));
  }
  overlay.oi = overlay.intersection[component_holding(intersection, anchor)];
  split_oi_boundary(maps, kProbeOffset * map_scale(free_world), overlay);
  return overlay;
}

bool covers(const Area& area, const Eigen::Vector2d& p) {
  if (area.outer.size() < 3) return false;
  return bg::covered_by(bgw::to_boost(p), bgw::to_boost(area));
}

bool covers(const Region& region, const Eigen::Vector2d& p) {
  return std::any_of(region.begin(), region.end(),
                     [&](const Area& area) { return covers(area, p); });
}

double region_size(const Region& region) {
  double size = 0.0;
  for (const Area& area : region) size += area_size(area);
  return size;
}

}  // namespace gridloc
