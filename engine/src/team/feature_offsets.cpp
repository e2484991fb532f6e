// Seed 003 eqs. 3.6-3.16, 3.19-3.23, 3.32-3.35 (and 6.8-6.18): the offsets of the robot from
// a feature's walls in the scan frame, and the Cartesian offsets from the robot to the
// feature's point in the map frame once its walls are matched to map walls.
#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "gridloc/engine/team/scan_features.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

bool two_walls(const ScanFeature& f) {
  return f.kind == FeatureKind::ConcaveCorner || f.kind == FeatureKind::ConvexCorner;
}

/// [0 0 1] x w: w turned by +90 deg (eqs. 3.6-3.7, 3.19, 3.32).
Eigen::Vector2d left_normal(const Eigen::Vector2d& w) {
  return {-w.y(), w.x()};
}

/// `w` as a unit direction; throws gridloc::Error naming `what` for a zero or non-finite one.
Eigen::Vector2d unit(const Eigen::Vector2d& w, const char* who, const char* what) {
  const double length = w.norm();
  if (!std::isfinite(length) || length < 1e-12) {
    throw Error(std::string(who) + ": " + what + " is no direction (zero or not finite)");
  }
  return w / length;
}

/// The matrix whose rows are a and b (eqs. 3.10-3.11, 3.22-3.23, 3.34-3.35); throws
/// gridloc::Error when they are parallel.
Eigen::Matrix2d rows(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const char* what) {
  Eigen::Matrix2d m;
  m.row(0) = a.transpose();
  m.row(1) = b.transpose();
  if (std::abs(m.determinant()) < 1e-9) {
    throw Error(std::string("cartesian_offsets: ") + what + " are parallel");
  }
  return m;
}

/// Row vector v times T (eq. 3.14), as a column.
Eigen::Vector2d times(const Eigen::Vector2d& v, const Eigen::Matrix2d& t) {
  return (v.transpose() * t).transpose();
}

}  // namespace

FeatureOffsets feature_offsets(const ScanFeature& feature) {
  const Eigen::Vector2d w1 = unit(feature.wall1, "feature_offsets", "wall1");
  const Eigen::Vector2d n1 = left_normal(w1);
  FeatureOffsets o;
  o.offset1 = feature.point.dot(n1) * n1;  // eqs. 3.8, 3.20, 3.33
  if (two_walls(feature)) {
    const Eigen::Vector2d n2 = left_normal(unit(feature.wall2, "feature_offsets", "wall2"));
    o.offset2 = feature.point.dot(n2) * n2;  // eq. 3.9
  } else if (feature.kind == FeatureKind::ConvexCornerOneWall) {
    o.offset2 = feature.point.dot(w1) * w1;  // eq. 3.21
  }
  return o;
}

Eigen::Vector2d cartesian_offsets(const ScanFeature& feature, const Eigen::Vector2d& env_wall1,
                                  const Eigen::Vector2d& env_wall2) {
  const FeatureOffsets o = feature_offsets(feature);
  const Eigen::Vector2d w1 = unit(feature.wall1, "cartesian_offsets", "wall1");
  const Eigen::Vector2d e1 = unit(env_wall1, "cartesian_offsets", "env_wall1");
  if (!two_walls(feature)) {
    // Eqs. 3.22-3.23, 3.34-3.35: the rows are a wall and its normal, so T is the rotation from
    // the scan to the map, and the offsets (normal and along the wall, or the normal alone for
    // a wall) add up to the feature's point (eqs. 3.14-3.16).
    const Eigen::Matrix2d t = rows(w1, left_normal(w1), "the feature's walls").inverse() *
                              rows(e1, left_normal(e1), "the map walls");
    return times(o.offset1, t) + times(o.offset2, t);
  }
  const Eigen::Vector2d w2 = unit(feature.wall2, "cartesian_offsets", "wall2");
  const Eigen::Vector2d e2 = unit(env_wall2, "cartesian_offsets", "env_wall2");
  const Eigen::Matrix2d t =
      rows(w1, w2, "the feature's walls").inverse() * rows(e1, e2, "the map walls");  // eq. 3.13
  // Eq. 3.14 turns offset_i = d_i n_i into offset_a = d_1 (n_1 T), offset_b = d_2 (n_2 T).
  // Eqs. 3.15-3.16 add them, which gives the corner only when its walls are perpendicular; in
  // general the corner is the point whose offsets along n_1 T and n_2 T are d_1 and d_2 (the
  // sum again for perpendicular walls).
  const Eigen::Vector2d n1 = left_normal(w1), n2 = left_normal(w2);
  Eigen::Matrix2d normals;
  normals.row(0) = times(n1, t).transpose();
  normals.row(1) = times(n2, t).transpose();
  const Eigen::Vector2d distances(o.offset1.dot(n1), o.offset2.dot(n2));
  return normals.inverse() * distances;
}

}  // namespace gridloc
