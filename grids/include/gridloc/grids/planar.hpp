#pragma once
/// Plane geometry shared by every family (issue 31): one definition of each helper, the
/// callers keeping their own tolerances.
#include <Eigen/Core>

namespace gridloc {

/// The 2-D cross product a.x b.y - a.y b.x: > 0 when b lies counter-clockwise of a, the
/// signed area of the parallelogram they span.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace gridloc
