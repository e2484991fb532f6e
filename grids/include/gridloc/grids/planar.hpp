#pragma once
/// Plane geometry shared by every family (issue 31): one definition of each helper, the
/// callers keeping their own tolerances.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace gridloc {

/// A segment from a to b: a wall, a polygon's edge.
struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

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

/// The distance from p to the nearest of segment_at(0), ..., segment_at(count - 1) (each
/// with ends a and b, such as a Segment2), or +infinity when count = 0.
template <class SegmentAt>
double distance_to_nearest(const Eigen::Vector2d& p, std::size_t count,
                           const SegmentAt& segment_at) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < count; ++k) {
    const auto& segment = segment_at(k);
    nearest = std::min(nearest, distance_to_segment(p, segment.a, segment.b));
  }
  return nearest;
}

/// What a ray cast counts as meeting a segment, each caller's own: a segment with
/// |cross(direction, b - a)| < parallel is parallel to the ray (not met); a hit at
/// a + u (b - a) is on it for u in [-slack, 1 + slack] (slack lets a ray through a vertex two
/// segments share meet one of them); a hit at the origin itself (t = 0) counts only when
/// origin_counts.
struct RayTolerances {
  double parallel = 0.0;
  double slack = 0.0;
  bool origin_counts = false;
};

/// The distance t along `direction` (in units of its length) from `origin` to the nearest of
/// `segments` it meets, or +infinity: origin + t direction = a + u (b - a) solved by Cramer's
/// rule, with the caller's tolerances.
inline double ray_distance(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                           std::span<const Segment2> segments, const RayTolerances& tolerances) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Segment2& segment : segments) {
    const Eigen::Vector2d along = segment.b - segment.a;
    const double denominator = cross(direction, along);
    if (std::abs(denominator) < tolerances.parallel) continue;
    const Eigen::Vector2d to_start = segment.a - origin;
    const double t = cross(to_start, along) / denominator;
    const double u = cross(to_start, direction) / denominator;
    const bool ahead = tolerances.origin_counts ? t >= 0.0 : t > 0.0;
    if (ahead && u >= -tolerances.slack && u <= 1.0 + tolerances.slack) {
      nearest = std::min(nearest, t);
    }
  }
  return nearest;
}

/// Where the line through p along u meets the line through q along v:
/// p + u cross(q - p, v) / cross(u, v). The lines must not be parallel (cross(u, v) != 0);
/// each caller says how near parallel is too near.
inline Eigen::Vector2d line_intersection(const Eigen::Vector2d& p, const Eigen::Vector2d& u,
                                         const Eigen::Vector2d& q, const Eigen::Vector2d& v) {
  return p + u * (cross(q - p, v) / cross(u, v));
}

/// A total-least-squares line: the points' centroid and the unit direction that minimizes
/// their orthogonal distances (the scatter matrix's principal eigenvector; its sign is the
/// solver's, each caller orients it).
struct FittedLine {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
};

/// The total-least-squares line through point(0), ..., point(count - 1), count >= 1 (one
/// point, or all alike: any direction).
template <class PointAt>
FittedLine total_least_squares_line(std::size_t count, const PointAt& point) {
  FittedLine line;
  for (std::size_t k = 0; k < count; ++k) line.centroid += point(k);
  line.centroid /= static_cast<double>(count);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector2d d = point(k) - line.centroid;
    scatter += d * d.transpose();
  }
  line.direction = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(1);
  return line;
}

}  // namespace gridloc
