#pragma once
// Shared by the view tests: hand-made rooms, random polygons with holes (fixed seeds) and an
// exact brute-force ray caster over every wall of an area.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"
#include "random_cases.hpp"

namespace gridloc::test {

/// The axis-aligned rectangle [x0, x1] x [y0, y1], counter-clockwise.
inline Polygon rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

/// The ring reversed (counter-clockwise <-> clockwise).
inline Polygon reversed(Polygon ring) {
  return Polygon(ring.rbegin(), ring.rend());
}

inline double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

/// Distance along the ray origin + s u (u unit) to the segment a-b (ends included), or +inf.
inline double ray_to_segment(const Eigen::Vector2d& origin, const Eigen::Vector2d& u,
                             const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a, w = a - origin;
  const double denominator = cross2(u, d);
  if (denominator == 0.0) return std::numeric_limits<double>::infinity();
  const double s = cross2(w, d) / denominator, t = cross2(w, u) / denominator;
  if (s < 0.0 || t < -1e-12 || t > 1.0 + 1e-12) return std::numeric_limits<double>::infinity();
  return s;
}

/// The nearest wall of the area along the ray, by testing every edge.
inline double cast_ray(const Area& area, const Eigen::Vector2d& origin, const Eigen::Vector2d& u) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const PlanarSegment& edge : area_edges(area)) {
    nearest = std::min(nearest, ray_to_segment(origin, u, edge.a, edge.b));
  }
  return nearest;
}

inline double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                     const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

/// Whether p lies strictly in the area (inside outer, outside every hole).
inline bool strictly_inside(const Area& area, const Eigen::Vector2d& p) {
  if (!inside(area.outer, p)) return false;
  for (const Polygon& hole : area.holes) {
    if (inside(hole, p)) return false;
  }
  return true;
}

/// A star-shaped room about the origin (radii 2-5, jittered angles) with up to 4 square
/// holes of side 0.3 near the centre (clockwise).
inline Area random_star_room(std::mt19937& rng) {
  const int n = uniform_int(rng, 8, 40);
  Area area;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + uniform_real(rng, 0.0, 0.9)) / n;
    const double radius = uniform_real(rng, 2.0, 5.0);
    area.outer.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  std::vector<Eigen::Vector2d> centres;
  const int holes = uniform_int(rng, 0, 4);
  for (int attempt = 0; attempt < 50 && static_cast<int>(centres.size()) < holes; ++attempt) {
    const Eigen::Vector2d c(uniform_real(rng, -1.0, 1.0), uniform_real(rng, -1.0, 1.0));
    bool apart = true;
    for (const Eigen::Vector2d& other : centres) apart = apart && (c - other).norm() > 0.5;
    if (!apart) continue;
    centres.push_back(c);
    area.holes.push_back(
        reversed(rectangle(c.x() - 0.15, c.y() - 0.15, c.x() + 0.15, c.y() + 0.15)));
  }
  return area;
}

/// An x-monotone rectilinear room over `columns` unit columns: floor heights in {0..3}, ceiling
/// heights in {5..8} (equal neighbours leave collinear vertices), unit square holes at y in
/// [3.5, 4.5] in some columns.
inline Area random_rectilinear_room(std::mt19937& rng, int columns) {
  std::vector<int> floor(columns), ceiling(columns);
  for (int i = 0; i < columns; ++i) {
    floor[i] = uniform_int(rng, 0, 3);
    ceiling[i] = uniform_int(rng, 5, 8);
  }
  Area area;
  for (int i = 0; i < columns; ++i) {  // floor, left to right
    area.outer.emplace_back(i, floor[i]);
    area.outer.emplace_back(i + 1, floor[i]);
  }
  for (int i = columns - 1; i >= 0; --i) {  // ceiling, right to left
    area.outer.emplace_back(i + 1, ceiling[i]);
    area.outer.emplace_back(i, ceiling[i]);
  }
  area.outer.erase(std::unique(area.outer.begin(), area.outer.end()), area.outer.end());
  for (int i = 1; i + 1 < columns; i += 3) {
    if (uniform_int(rng, 0, 1) == 0) {
      area.holes.push_back(reversed(rectangle(i + 0.25, 3.5, i + 0.75, 4.25)));
    }
  }
  return area;
}

/// A uniform random point strictly inside the area, at least `clearance` from every wall.
inline Eigen::Vector2d random_inside(std::mt19937& rng, const Area& area, double clearance = 1e-3) {
  Eigen::Vector2d lo = area.outer.front(), hi = area.outer.front();
  for (const Eigen::Vector2d& p : area.outer) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (;;) {
    const Eigen::Vector2d p(uniform_real(rng, lo.x(), hi.x()), uniform_real(rng, lo.y(), hi.y()));
    if (!strictly_inside(area, p)) continue;
    bool clear = true;
    for (const PlanarSegment& e : area_edges(area)) {
      clear = clear && point_segment_distance(p, e.a, e.b) > clearance;
    }
    if (clear) return p;
  }
}

}  // namespace gridloc::test
