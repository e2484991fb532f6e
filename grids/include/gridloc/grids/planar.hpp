#pragma once
/// Plane geometry shared by every family (issue 31): one definition of each helper, the
/// callers keeping their own tolerances.
#include <Eigen/Core>
#include <cmath>

namespace gridloc {

/// The 2-D cross product a.x b.y - a.y b.x: > 0 when b lies counter-clockwise of a, the
/// signed area of the parallelogram they span.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The squared distance from p to the segment a-b (a point when a = b), with one division
/// at most: the ends when p projects beyond them, else the perpendicular.
inline double squared_distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a, w = p - a;
  const double along = w.dot(d);
  if (along <= 0.0) return w.squaredNorm();
  const double length2 = d.squaredNorm();
  if (along >= length2) return (p - b).squaredNorm();
  const double off = cross(d, w);
  return off * off / length2;
}

/// The distance from p to the segment a-b (a point when a = b).
inline double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                  const Eigen::Vector2d& b) {
  return std::sqrt(squared_distance_to_segment(p, a, b));
}

}  // namespace gridloc
