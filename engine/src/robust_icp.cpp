// Robust scan-to-scan ICP of seed 004 §3: segmentation and C_f (§3.2), point-to-tangent-line
// distances (eq. (2)-(4)), Huber's M-estimator with the previous iteration's scale
// (eq. (5)-(6)), and an iterative solve of the weighted normal equations (eq. (7)).
#include "gridloc/engine/robust_icp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

void check_points(const std::vector<Eigen::Vector2d>& points, const char* name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw Error(std::string("match_scans: ") + name + " point " + std::to_string(i) +
                  " is not finite");
    }
  }
}

void check_positive(double v, const char* field) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw Error(std::string("IcpOptions.") + field + " must be positive and finite, got " +
                std::to_string(v));
  }
}

void check_options(const IcpOptions& o) {
  check_positive(o.gap_m, "gap_m");
  check_positive(o.resolution_m, "resolution_m");
  check_positive(o.huber_k, "huber_k");
  check_positive(o.min_scale_m, "min_scale_m");
  check_positive(o.max_correspondence_m, "max_correspondence_m");
  if (o.min_segment_points < 1) throw Error("IcpOptions.min_segment_points must be >= 1, got 0");
  if (o.max_iterations < 1) {
    throw Error("IcpOptions.max_iterations must be >= 1, got " + std::to_string(o.max_iterations));
  }
  if (!(o.converged_xy_m >= 0.0) || !(o.converged_theta_rad >= 0.0)) {
    throw Error("IcpOptions.converged_xy_m and converged_theta_rad must be >= 0, got " +
                std::to_string(o.converged_xy_m) + " and " + std::to_string(o.converged_theta_rad));
  }
}

/// Total-least-squares line of points[begin, end): centroid, unit direction, mean |distance|.
void fit_line(const std::vector<Eigen::Vector2d>& points, Segment& s) {
  const double n = static_cast<double>(s.size());
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (std::size_t i = s.begin; i < s.end; ++i) c += points[i];
  c /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t i = s.begin; i < s.end; ++i)
    cov += (points[i] - c) * (points[i] - c).transpose();
  s.centroid = c;
  if (s.size() >= 2) {
    // Largest eigenvector of the scatter matrix = direction minimizing orthogonal distances
    // (seed 004 eq. (9) fits y = Ax + B; total least squares also handles vertical segments).
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    s.direction = eig.eigenvectors().col(1).normalized();
  }
  const Eigen::Vector2d normal(-s.direction.y(), s.direction.x());
  double sum = 0.0;
  for (std::size_t i = s.begin; i < s.end; ++i) sum += std::abs(normal.dot(points[i] - c));
  s.mean_distance_m = sum / n;  // seed 004 eq. (10): d_m
}

/// Uniform-grid buckets of the reference points (cell = max correspondence distance), so a
/// 3 x 3 block of cells holds every point within that distance of a query.
class BucketGrid {
 public:
  BucketGrid(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& usable,
             double cell)
      : points_(points), cell_(cell) {
    lo_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo_;
    for (int i : usable) {
      lo_ = lo_.cwiseMin(points[i]);
      hi = hi.cwiseMax(points[i]);
    }
    // At most 512 cells a side: a cell wider than the search radius still covers it.
    cell_ = std::max(cell_, (hi - lo_).maxCoeff() / 512.0);
    nx_ = static_cast<int>((hi.x() - lo_.x()) / cell_) + 1;
    ny_ = static_cast<int>((hi.y() - lo_.y()) / cell_) + 1;
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int i : usable) ++start_[cell_index(points[i]) + 1];
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    index_.resize(usable.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int i : usable) index_[fill[cell_index(points[i])]++] = i;  // ascending within a cell
  }

  /// Index of the nearest usable point within `max_dist`, or -1; ties go to the lowest index.
  int nearest(const Eigen::Vector2d& q, double max_dist) const {
    // Clamped in double first, so a query far outside the grid cannot overflow the cast.
    const int cx = static_cast<int>(
        std::clamp(std::floor((q.x() - lo_.x()) / cell_), -2.0, static_cast<double>(nx_ + 1)));
    const int cy = static_cast<int>(
        std::clamp(std::floor((q.y() - lo_.y()) / cell_), -2.0, static_cast<double>(ny_ + 1)));
    int best = -1;
    double best_d2 = max_dist * max_dist;
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, ny_ - 1); ++y) {
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, nx_ - 1); ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
        for (int k = start_[c]; k < start_[c + 1]; ++k) {
          const int i = index_[k];
          const double d2 = (points_[i] - q).squaredNorm();
          if (d2 < best_d2 || (d2 == best_d2 && best >= 0 && i < best)) {
            best_d2 = d2;
            best = i;
          }
        }
      }
    }
    return best;
  }

 private:
  std::size_t cell_index(const Eigen::Vector2d& p) const {
    const int x = std::min(static_cast<int>((p.x() - lo_.x()) / cell_), nx_ - 1);
    const int y = std::min(static_cast<int>((p.y() - lo_.y()) / cell_), ny_ - 1);
    return static_cast<std::size_t>(y) * nx_ + x;
  }

  const std::vector<Eigen::Vector2d>& points_;
  double cell_;
  Eigen::Vector2d lo_;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;
  std::vector<int> index_;
};

/// One point-to-tangent-line pair: transformed matching point q, tangent normal n, residual r.
struct Pair {
  Eigen::Vector2d q;
  Eigen::Vector2d n;
  double r;
};

struct Reference {
  const std::vector<Eigen::Vector2d>& points;
  std::vector<int> segment_of;  // segment id of each point
  BucketGrid grid;
};

/// Pairs of the matching points `src` under pose (R, t) with the reference's tangent lines.
/// The tangent at the nearest reference point i is the chord to its neighbour i-1 or i+1 in
/// the same segment, whichever line passes closer to q (seed 004 eq. (3): the tangential line
/// of the other curve; the one-sided chord keeps a corner from bending the tangent).
void make_pairs(const Reference& ref, const std::vector<Eigen::Vector2d>& src,
                const Eigen::Matrix2d& R, const Eigen::Vector2d& t, double max_dist,
                std::vector<Pair>& pairs) {
  pairs.clear();
  const int n = static_cast<int>(ref.points.size());
  for (const auto& p : src) {
    const Eigen::Vector2d q = R * p + t;
    const int i = ref.grid.nearest(q, max_dist);
    if (i < 0) continue;
    double best_r = std::numeric_limits<double>::infinity();
    Eigen::Vector2d best_n = Eigen::Vector2d::Zero();
    for (int j : {i - 1, i + 1}) {
      if (j < 0 || j >= n || ref.segment_of[j] != ref.segment_of[i]) continue;
      const Eigen::Vector2d d = ref.points[j] - ref.points[i];
      const double len = d.norm();
      if (len <= 0.0) continue;
      const Eigen::Vector2d normal(-d.y() / len, d.x() / len);
      const double r = normal.dot(q - ref.points[i]);
      if (std::abs(r) < std::abs(best_r)) {
        best_r = r;
        best_n = normal;
      }
    }
    if (std::isfinite(best_r)) pairs.push_back({q, best_n, best_r});
  }
}

}  // namespace

double shape_complexity(double mean_distance_m, double resolution_m) {
  // Seed 004 eq. (11): C_f = (d_m + R_m) / (10 R_m), and 1 where that exceeds 1. A straight
  // segment (d_m = 0) gets 0.1; one bending by 9 R_m or more on average gets 1.
  return std::min(1.0, (mean_distance_m + resolution_m) / (10.0 * resolution_m));
}

std::size_t matching_point_count(double complexity, std::size_t segment_size) {
  // Seed 004 eq. (12) is lost in the scanned text; "the number of optimal matching points with
  // respect to the segment" is read as C_f times the segment's size, rounded up, so a straight
  // wall keeps one point in ten and a cluttered segment keeps all of its points.
  if (segment_size == 0) return 0;
  const auto n =
      static_cast<std::size_t>(std::ceil(complexity * static_cast<double>(segment_size) - 1e-9));
  return std::clamp<std::size_t>(n, 1, segment_size);
}

std::vector<Segment> segment_scan(const std::vector<Eigen::Vector2d>& points, double gap_m,
                                  double resolution_m) {
  check_positive(gap_m, "gap_m");
  check_positive(resolution_m, "resolution_m");
  std::vector<Segment> segments;
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= points.size(); ++i) {
    // Seed 004 §3.2: points within the gap (8 cm = 2 pixels) of the previous one continue the
    // segment.
    if (i < points.size() && (points[i] - points[i - 1]).norm() <= gap_m) continue;
    if (i > begin) {
      Segment s;
      s.begin = begin;
      s.end = i;
      fit_line(points, s);
      s.complexity = shape_complexity(s.mean_distance_m, resolution_m);
      s.matching_points = matching_point_count(s.complexity, s.size());
      segments.push_back(s);
    }
    begin = i;
  }
  return segments;
}

double huber_weight(double r, double k) {
  const double a = std::abs(r);
  return a <= k ? 1.0 : k / a;
}

double residual_scale(const std::vector<double>& r, HuberScale rule, double floor_m) {
  if (r.empty()) return floor_m;
  double sigma = 0.0;
  if (rule == HuberScale::kMad) {
    std::vector<double> a(r.size());
    std::transform(r.begin(), r.end(), a.begin(), [](double v) { return std::abs(v); });
    const auto mid = a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2);
    std::nth_element(a.begin(), mid, a.end());
    sigma = 1.4826 * *mid;
  } else {
    double mean = 0.0;
    for (double v : r) mean += v;
    mean /= static_cast<double>(r.size());
    double var = 0.0;
    for (double v : r) var += (v - mean) * (v - mean);
    sigma = std::sqrt(var / static_cast<double>(r.size()));
  }
  return std::max(sigma, floor_m);
}

IcpResult match_scans(const std::vector<Eigen::Vector2d>& reference,
                      const std::vector<Eigen::Vector2d>& current, const Pose2& initial,
                      const IcpOptions& options) {
  check_options(options);
  if (reference.size() < 3) {
    throw Error("match_scans: reference scan has " + std::to_string(reference.size()) +
                " points, needs at least 3");
  }
  if (current.size() < 3) {
    throw Error("match_scans: current scan has " + std::to_string(current.size()) +
                " points, needs at least 3");
  }
  check_points(reference, "reference");
  check_points(current, "current");
  if (!std::isfinite(initial.x) || !std::isfinite(initial.y) || !std::isfinite(initial.theta)) {
    throw Error("match_scans: initial pose is not finite");
  }

  // Reference: points in segments of >= 2 points carry a tangent (seed 004 eq. (3)).
  const auto ref_segments = segment_scan(reference, options.gap_m, options.resolution_m);
  std::vector<int> segment_of(reference.size(), -1);
  std::vector<int> usable;
  for (std::size_t s = 0; s < ref_segments.size(); ++s) {
    for (std::size_t i = ref_segments[s].begin; i < ref_segments[s].end; ++i) {
      segment_of[i] = static_cast<int>(s);
      if (ref_segments[s].size() >= 2) usable.push_back(static_cast<int>(i));
    }
  }
  if (usable.size() < 3) {
    throw Error("match_scans: reference scan has no segment of 2 or more points within gap_m = " +
                std::to_string(options.gap_m) + " m");
  }
  const Reference ref{reference, std::move(segment_of),
                      BucketGrid(reference, usable, options.max_correspondence_m)};

  // Current: the matching points, N_s per segment spread evenly along it (seed 004 §3.2).
  // Seed 004 puts the control points on the previous curve and the tangents on the current
  // one; here the roles are swapped so the result is directly the pose of `current` in the
  // reference frame (the same problem, with the tangents on the scan we index once).
  std::vector<Eigen::Vector2d> src;
  for (const auto& s : segment_scan(current, options.gap_m, options.resolution_m)) {
    if (s.size() < options.min_segment_points) continue;
    const std::size_t ns = options.use_complexity ? s.matching_points : s.size();
    for (std::size_t j = 0; j < ns; ++j) {
      src.push_back(current[s.begin + (2 * j + 1) * s.size() / (2 * ns)]);
    }
  }
  if (src.size() < 3) {
    throw Error("match_scans: current scan gives " + std::to_string(src.size()) +
                " matching points, needs at least 3 (check gap_m and min_segment_points)");
  }

  IcpResult result;
  double theta = initial.theta;
  Eigen::Vector2d t(initial.x, initial.y);
  std::vector<Pair> pairs;
  std::vector<double> residuals;
  double sigma = options.min_scale_m;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(theta).toRotationMatrix();
    make_pairs(ref, src, R, t, options.max_correspondence_m, pairs);
    if (pairs.size() < 3) break;
    residuals.resize(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) residuals[k] = pairs[k].r;
    // sigma of the errors at the pose of the previous step (seed 004 eq. (5)-(6)).
    sigma = residual_scale(residuals, options.scale, options.min_scale_m);

    // Gauss-Newton on a left increment (dx, dy, dtheta) about the reference origin: the
    // residual n.(q - m) has gradient (n_x, n_y, n.(-q_y, q_x)). Seed 004 eq. (7) solves the
    // same weighted normal equations in the linear parameters (a, b, c, d) of eq. (1); the
    // 3-parameter form keeps the rotation rigid.
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const auto& p : pairs) {
      const double w = options.robust ? huber_weight(p.r / sigma, options.huber_k) : 1.0;
      const Eigen::Vector3d J(p.n.x(), p.n.y(), p.n.dot(Eigen::Vector2d(-p.q.y(), p.q.x())));
      H.noalias() += w * J * J.transpose();
      g.noalias() += w * p.r * J;
    }
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(H);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-12) break;  // degenerate geometry
    const Eigen::Vector3d delta = -ldlt.solve(g);
    const Eigen::Rotation2Dd dR(delta.z());
    t = dR * t + delta.head<2>();
    theta = normalize_angle(theta + delta.z());
    result.iterations = it + 1;
    if (delta.head<2>().norm() < options.converged_xy_m &&
        std::abs(delta.z()) < options.converged_theta_rad) {
      result.converged = true;
      break;
    }
  }

  // Final residuals at the returned pose.
  make_pairs(ref, src, Eigen::Rotation2Dd(theta).toRotationMatrix(), t,
             options.max_correspondence_m, pairs);
  result.pose = {t.x(), t.y(), theta};
  result.pairs = pairs.size();
  if (!pairs.empty()) {
    residuals.resize(pairs.size());
    double sum2 = 0.0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      residuals[k] = pairs[k].r;
      sum2 += pairs[k].r * pairs[k].r;
    }
    sigma = residual_scale(residuals, options.scale, options.min_scale_m);
    std::size_t inliers = 0;
    for (double r : residuals) inliers += std::abs(r) <= options.huber_k * sigma ? 1 : 0;
    result.rms_m = std::sqrt(sum2 / static_cast<double>(pairs.size()));
    result.inlier_share = static_cast<double>(inliers) / static_cast<double>(pairs.size());
  }
  result.scale_m = sigma;
  return result;
}

}  // namespace gridloc
