#pragma once
/// Boost.Geometry adapter of the disambiguation sources (private: never included by a public
/// header). Rings are counter-clockwise outer and clockwise holes, as gridloc's Area, and
/// closed (Boost repeats the first vertex at the end; Area does not).
#include <Eigen/Core>
// Boost 1.74 rescales coordinates to an integer grid in its set operations (its robustness
// policy). That moves computed crossings by about 1e-7 of the extent (an L room turned by
// 0.3 rad loses 4e-7 of its area), but without it (BOOST_GEOMETRY_NO_ROBUSTNESS) the overlay
// of look-alike copies with coinciding walls came out empty on 5 of 20 random offices (seed
// 002's protocol): we keep it.
// GCC 12 sees a false "may be used uninitialized" in Boost 1.74's rescale policy.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/segment.hpp>
#include <boost/geometry/index/rtree.hpp>
#pragma GCC diagnostic pop
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"

namespace gridloc::boost_geometry {

namespace bg = boost::geometry;

using Point = bg::model::d2::point_xy<double>;
using Ring = bg::model::ring<Point, false, true>;             ///< counter-clockwise, closed
using BoostPolygon = bg::model::polygon<Point, false, true>;  ///< ccw outer, cw holes, closed
using MultiPolygon = bg::model::multi_polygon<BoostPolygon>;
using Box = bg::model::box<Point>;
using BoostSegment = bg::model::segment<Point>;

inline Point to_boost(const Eigen::Vector2d& p) {
  return {p.x(), p.y()};
}

inline Eigen::Vector2d to_eigen(const Point& p) {
  return {p.x(), p.y()};
}

/// A gridloc ring (open) as a closed Boost ring.
template <typename BoostRing>
void fill_ring(const Polygon& ring, BoostRing& out) {
  out.clear();
  out.reserve(ring.size() + 1);
  for (const Eigen::Vector2d& vertex : ring) out.push_back(to_boost(vertex));
  if (!ring.empty()) out.push_back(to_boost(ring.front()));
}

/// An Area as a Boost polygon, orientation corrected (bg::correct).
inline BoostPolygon to_boost(const Area& area) {
  BoostPolygon polygon;
  fill_ring(area.outer, polygon.outer());
  polygon.inners().resize(area.holes.size());
  for (std::size_t i = 0; i < area.holes.size(); ++i) {
    fill_ring(area.holes[i], polygon.inners()[i]);
  }
  bg::correct(polygon);
  return polygon;
}

/// A closed Boost ring as a gridloc ring: the closing vertex and repeated vertices dropped.
template <typename BoostRing>
Polygon to_ring(const BoostRing& ring) {
  Polygon out;
  out.reserve(ring.size());
  for (const Point& p : ring) {
    const Eigen::Vector2d vertex = to_eigen(p);
    if (out.empty() || vertex != out.back()) out.push_back(vertex);
  }
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

inline Area to_area(const BoostPolygon& polygon) {
  Area area{to_ring(polygon.outer()), {}};
  area.holes.reserve(polygon.inners().size());
  for (const auto& inner : polygon.inners()) area.holes.push_back(to_ring(inner));
  return area;
}

}  // namespace gridloc::boost_geometry
