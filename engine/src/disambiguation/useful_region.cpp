// Seed 002 §IV-D step 6: the useful region U, with Boost.Geometry for the unions and clips.
// GCC 12 flags Boost 1.74's rescale policy (get_rescale_policy.hpp) as maybe-uninitialized:
// a false positive inside Boost, silenced for its headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#pragma GCC diagnostic pop
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <cmath>
#include <string>

#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {

namespace {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint, false, true>;  // counter-clockwise, closed
using BgMultiPolygon = bg::model::multi_polygon<BgPolygon>;

constexpr double kPullInside = 1e-7;  // samples sit this far inside oi (range_view.hpp)

BgPoint to_bg(const Eigen::Vector2d& p) {
  return {p.x(), p.y()};
}

template <typename BgRing>
void fill_ring(const Polygon& ring, BgRing& out) {
  for (const Eigen::Vector2d& p : ring) out.push_back(to_bg(p));
  if (!ring.empty()) out.push_back(to_bg(ring.front()));
}

BgPolygon to_bg(const Area& area) {
  BgPolygon polygon;
  fill_ring(area.outer, polygon.outer());
  for (const Polygon& hole : area.holes) {
    polygon.inners().emplace_back();
    fill_ring(hole, polygon.inners().back());
  }
  bg::correct(polygon);
  return polygon;
}

BgPolygon to_bg(const Polygon& ring) {
  return to_bg(Area{ring, {}});
}

template <typename BgRing>
Polygon from_bg(const BgRing& ring) {
  Polygon out;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) out.emplace_back(ring[i].x(), ring[i].y());
  return out;
}

Region to_region(const BgMultiPolygon& multi) {
  Region region;
  for (const BgPolygon& polygon : multi) {
    Area area{from_bg(polygon.outer()), {}};
    for (const auto& inner : polygon.inners()) area.holes.push_back(from_bg(inner));
    region.push_back(std::move(area));
  }
  return region;
}

/// The unit normal of the edge pointing into oi: the side whose point 1e-7 off the edge's
/// midpoint lies in oi.
Eigen::Vector2d inward_normal(const BgPolygon& oi, const PlanarSegment& edge, std::size_t index) {
  const Eigen::Vector2d direction = edge.b - edge.a;
  if (!(direction.norm() > 0.0)) {
    throw Error("useful_region: internal edge " + std::to_string(index) + " has zero length");
  }
  Eigen::Vector2d left = Eigen::Vector2d(-direction.y(), direction.x()).normalized();
  const Eigen::Vector2d middle = 0.5 * (edge.a + edge.b);
  if (bg::within(to_bg(Eigen::Vector2d(middle + kPullInside * left)), oi)) return left;
  if (bg::within(to_bg(Eigen::Vector2d(middle - kPullInside * left)), oi)) return -left;
  throw Error("useful_region: internal edge " + std::to_string(index) +
              " does not lie on oi's boundary");
}

/// Seed 002 Fig. 6, inner approximation: the union of the visibility polygons of points
/// spread along the edge (interval midpoints), pulled into oi along `inward`.
BgMultiPolygon weak_visibility(const Area& oi, const BgPolygon& oi_bg, const PlanarSegment& edge,
                               const Eigen::Vector2d& inward, double range, int samples) {
  BgMultiPolygon seen;
  for (int k = 0; k < samples; ++k) {
    const double t = (k + 0.5) / samples;
    const Eigen::Vector2d point = edge.a + t * (edge.b - edge.a) + kPullInside * inward;
    if (!bg::within(to_bg(point), oi_bg)) continue;
    const Polygon ring = visibility_polygon(oi, point, range);
    if (ring.size() < 3) continue;
    BgMultiPolygon merged;
    bg::union_(seen, to_bg(ring), merged);
    seen = std::move(merged);
  }
  return seen;
}

/// Seed 002 §IV-D step 6's "infinitely long rectangle": along the edge's line, `length` to
/// each side of its midpoint, `width` deep on oi's side.
BgPolygon edge_rectangle(const PlanarSegment& edge, const Eigen::Vector2d& inward, double length,
                         double width) {
  const Eigen::Vector2d along = (edge.b - edge.a).normalized();
  const Eigen::Vector2d middle = 0.5 * (edge.a + edge.b);
  const Eigen::Vector2d base0 = middle - length * along, base1 = middle + length * along;
  return to_bg(Polygon{base0, base1, base1 + width * inward, base0 + width * inward});
}

double bounding_box_diagonal(const Area& oi) {
  bg::model::box<BgPoint> box;
  bg::envelope(to_bg(oi.outer), box);
  return bg::distance(box.min_corner(), box.max_corner());
}

void check_useful_region_input(const Area& oi, double range, int samples_per_edge) {
  if (oi.outer.size() < 3) throw Error("useful_region: oi's outer ring has < 3 vertices");
  if (!(range > 0.0)) {
    throw Error("useful_region: range must be > 0, got " + std::to_string(range));
  }
  if (samples_per_edge < 1) {
    throw Error("useful_region: samples_per_edge must be >= 1, got " +
                std::to_string(samples_per_edge));
  }
}

}  // namespace

Region useful_region(const Area& oi, const std::vector<PlanarSegment>& internal_edges, double range,
                     int samples_per_edge) {
  check_useful_region_input(oi, range, samples_per_edge);
  const BgPolygon oi_bg = to_bg(oi);
  const double length = 2.0 * bounding_box_diagonal(oi);
  BgMultiPolygon useful;
  for (std::size_t i = 0; i < internal_edges.size(); ++i) {
    const PlanarSegment& edge = internal_edges[i];
    const Eigen::Vector2d inward = inward_normal(oi_bg, edge, i);
    BgMultiPolygon seen = weak_visibility(oi, oi_bg, edge, inward, range, samples_per_edge);
    if (std::isfinite(range)) {  // seed 002 §IV-D step 6: clipped by a factor d
      BgMultiPolygon clipped;
      bg::intersection(seen, edge_rectangle(edge, inward, length, range), clipped);
      seen = std::move(clipped);
    }
    BgMultiPolygon merged;
    bg::union_(useful, seen, merged);
    useful = std::move(merged);
  }
  return to_region(useful);
}

}  // namespace gridloc
