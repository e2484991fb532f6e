// Robust scan-to-scan and scan-to-map ICP of seed 004 §3: point-to-tangent-line distances
// (eq. (2)-(4)), Huber's M-estimator with the previous iteration's scale (eq. (5)-(6)), and an
// iterative solve of the weighted normal equations (eq. (7)).
#include "gridloc/engine/icp/robust_icp.hpp"

#include "gridloc/engine/icp/map_contour.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/breakpoints.hpp"
#include "point_buckets.hpp"
#include "scan_segments.hpp"

namespace gridloc {
using namespace icp_detail;
namespace {

void check_points(const std::vector<Eigen::Vector2d>& points, const char* name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw Error(std::string("match_scans: ") + name + " point " + std::to_string(i) +
                  " is not finite");
    }
  }
}

}  // namespace

namespace icp_detail {

void check_positive(double v, const char* field) {
  require_positive(v, "IcpOptions", field);
}

}  // namespace icp_detail

void validate(const IcpOptions& options) {
  check_positive(options.gap_m, "gap_m");
  check_positive(options.resolution_m, "resolution_m");
  check_positive(options.huber_k, "huber_k");
  check_positive(options.min_scale_m, "min_scale_m");
  check_positive(options.max_correspondence_m, "max_correspondence_m");
  check_positive(options.fit_distance_m, "fit_distance_m");
  check_grazing_angle(options.breakpoint_angle_rad, "IcpOptions.breakpoint_angle_rad");
  if (options.min_segment_points < 1)
    throw Error("IcpOptions.min_segment_points must be >= 1, got 0");
  if (options.max_iterations < 1) {
    throw Error("IcpOptions.max_iterations must be >= 1, got " +
                std::to_string(options.max_iterations));
  }
  if (!(options.settled_xy_m >= 0.0) || !(options.settled_theta_rad >= 0.0)) {
    throw Error("IcpOptions.settled_xy_m and settled_theta_rad must be >= 0, got " +
                std::to_string(options.settled_xy_m) + " and " +
                std::to_string(options.settled_theta_rad));
  }
  if (!(options.converged_xy_m >= 0.0) || !(options.converged_theta_rad >= 0.0)) {
    throw Error("IcpOptions.converged_xy_m and converged_theta_rad must be >= 0, got " +
                std::to_string(options.converged_xy_m) + " and " +
                std::to_string(options.converged_theta_rad));
  }
}

namespace {

/// One point-to-tangent-line pair: transformed matching point q, tangent normal n, residual
/// r = n.(q - m) (seed 004 eq. (2)-(4)).
struct Pair {
  Eigen::Vector2d point;   ///< q
  Eigen::Vector2d normal;  ///< n
  double residual;         ///< r
};

/// What the matching points are matched against: points with a bucket index and a tangent
/// rule. A scan (segment_of set) takes the chord to a neighbour in the same segment; a map
/// contour (normals set) has a fixed normal per point.
struct Model {
  const std::vector<Eigen::Vector2d>& points;
  const detail::PointBuckets& buckets;
  const std::vector<int>* segment_of = nullptr;
  const std::vector<Eigen::Vector2d>* normals = nullptr;
};

/// Pairs of the matching points `src` under pose (R, t) with the model's tangent lines.
/// For a scan the tangent at the nearest reference point i is the chord to its neighbour i-1
/// or i+1 in the same segment, whichever line passes closer to q (seed 004 eq. (3): the
/// tangential line of the other curve; the one-sided chord keeps a corner from bending it).
void make_pairs(const Model& model, const std::vector<Eigen::Vector2d>& src,
                const Eigen::Matrix2d& R, const Eigen::Vector2d& t, double max_dist,
                std::vector<Pair>& pairs) {
  pairs.clear();
  const int n = static_cast<int>(model.points.size());
  for (const auto& p : src) {
    const Eigen::Vector2d q = R * p + t;
    const int i = model.buckets.nearest(q, max_dist);
    if (i < 0) continue;
    if (model.normals != nullptr) {
      const Eigen::Vector2d& normal = (*model.normals)[i];
      pairs.push_back({q, normal, normal.dot(q - model.points[i])});
      continue;
    }
    const std::vector<int>& segment_of = *model.segment_of;
    double best_r = std::numeric_limits<double>::infinity();
    Eigen::Vector2d best_n = Eigen::Vector2d::Zero();
    for (int j : {i - 1, i + 1}) {
      if (j < 0 || j >= n || segment_of[j] != segment_of[i]) continue;
      const Eigen::Vector2d d = model.points[j] - model.points[i];
      const double len = d.norm();
      if (len <= 0.0) continue;
      const Eigen::Vector2d normal(-d.y() / len, d.x() / len);
      const double r = normal.dot(q - model.points[i]);
      if (std::abs(r) < std::abs(best_r)) {
        best_r = r;
        best_n = normal;
      }
    }
    if (std::isfinite(best_r)) pairs.push_back({q, best_n, best_r});
  }
}

constexpr std::size_t kSettleSteps = 5;

/// The residual's gradient for an increment that turns about the pose's position t.
Eigen::Vector3d jacobian(const Pair& p, const Eigen::Vector2d& t) {
  const Eigen::Vector2d v = p.point - t;
  return {p.normal.x(), p.normal.y(), p.normal.dot(Eigen::Vector2d(-v.y(), v.x()))};
}

/// The covariance of a pose nothing constrains.
Eigen::Matrix3d unconstrained() {
  return Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()).asDiagonal();
}

/// Every pose of `history` within settled_xy_m and settled_theta_rad of the last.
bool settled(const std::vector<Pose2>& history, const IcpOptions& options) {
  const Pose2& last = history.back();
  return std::all_of(history.begin(), history.end(), [&](const Pose2& p) {
    return std::hypot(p.x - last.x, p.y - last.y) <= options.settled_xy_m &&
           std::abs(normalize_angle(p.theta - last.theta)) <= options.settled_theta_rad;
  });
}

}  // namespace

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

namespace {

void check_pose(const Pose2& initial, const char* who) {
  if (!std::isfinite(initial.x) || !std::isfinite(initial.y) || !std::isfinite(initial.theta)) {
    throw Error(std::string(who) + ": initial pose is not finite");
  }
}

/// The state of one solve(): the pose (heading theta, position t), the latest pairs and the
/// Huber scale of their residuals.
struct IcpState {
  double theta = 0.0;
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  std::vector<Pair> pairs;
  double sigma = 0.0;
};

/// The scale sigma of the pairs' residuals (seed 004 eq. (5)-(6)).
double pair_scale(const std::vector<Pair>& pairs, const IcpOptions& options) {
  std::vector<double> residuals(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) residuals[k] = pairs[k].residual;
  return residual_scale(residuals, options.scale, options.min_scale_m);
}

/// The Gauss-Newton increment (dx, dy, dtheta) of the pairs under Huber weights at scale
/// sigma, shortened to the correspondence reach; nullopt for degenerate geometry.
std::optional<Eigen::Vector3d> robust_step(const std::vector<Pair>& pairs, const Eigen::Vector2d& t,
                                           double sigma, const IcpOptions& options) {
  // Gauss-Newton on an increment (dx, dy, dtheta) that turns about the pose's own position
  // t: q' = R(dtheta) (q - t) + t + (dx, dy). The residual n.(q - m) then has gradient
  // (n_x, n_y, n.perp(q - t)), which does not grow with the distance of t from the model's
  // origin (a map in a far-off frame stays well conditioned), and the increment is the
  // pose's own change. Seed 004 eq. (7) solves the same weighted normal equations in the
  // linear parameters (a, b, c, d) of eq. (1); the 3-parameter form keeps the rotation rigid.
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (const auto& p : pairs) {
    const double w = options.robust ? huber_weight(p.residual / sigma, options.huber_k) : 1.0;
    const Eigen::Vector3d J = jacobian(p, t);
    H.noalias() += w * J * J.transpose();
    g.noalias() += w * p.residual * J;
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(H);
  if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-12) return std::nullopt;
  Eigen::Vector3d delta = -ldlt.solve(g);
  // A step longer than the correspondence reach leaves every pair it was computed from: a
  // nearly degenerate system (few pairs on one wall) would throw the pose away. Shortened.
  const double step = delta.head<2>().norm();
  if (step > options.max_correspondence_m) delta *= options.max_correspondence_m / step;
  return delta;
}

/// The robust iterations (seed 004 eq. (5)-(7)) from the state's pose, until converged or
/// settled (result.converged), out of pairs, degenerate or out of iterations.
void iterate(const Model& model, const std::vector<Eigen::Vector2d>& src, IcpState& state,
             const IcpOptions& options, IcpResult& result) {
  std::vector<Pose2> history;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(state.theta).toRotationMatrix();
    make_pairs(model, src, R, state.t, options.max_correspondence_m, state.pairs);
    if (state.pairs.size() < 3) break;
    // sigma of the errors at the pose of the previous step (seed 004 eq. (5)-(6)).
    state.sigma = pair_scale(state.pairs, options);
    const std::optional<Eigen::Vector3d> delta =
        robust_step(state.pairs, state.t, state.sigma, options);
    if (!delta) break;  // degenerate geometry
    state.t += delta->head<2>();
    state.theta = normalize_angle(state.theta + delta->z());
    result.iterations = it + 1;
    if (delta->head<2>().norm() < options.converged_xy_m &&
        std::abs(delta->z()) < options.converged_theta_rad) {
      result.converged = true;
      return;
    }
    // On real scans a few pairs can flip between two tangents forever: the pose then
    // cycles within a tiny region. Settled when the last kSettleSteps poses lie that close.
    history.push_back({state.t.x(), state.t.y(), state.theta});
    if (history.size() > kSettleSteps) history.erase(history.begin());
    if (history.size() == kSettleSteps && settled(history, options)) {
      result.converged = true;
      return;
    }
  }
}

/// The result at the state's final pose: its pairs, rms and fitting pairs, the scale and
/// share of inliers, and their Gauss-Newton covariance when they constrain the pose.
void final_fit(const Model& model, const std::vector<Eigen::Vector2d>& src, IcpState& state,
               const IcpOptions& options, IcpResult& result) {
  make_pairs(model, src, Eigen::Rotation2Dd(state.theta).toRotationMatrix(), state.t,
             options.max_correspondence_m, state.pairs);
  const std::vector<Pair>& pairs = state.pairs;
  result.pose = {state.t.x(), state.t.y(), state.theta};
  result.pairs = pairs.size();
  result.matching_points = src.size();
  if (!pairs.empty()) {
    double sum2 = 0.0;
    for (const auto& p : pairs) sum2 += p.residual * p.residual;
    state.sigma = pair_scale(pairs, options);
    std::size_t inliers = 0;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (const auto& p : pairs) {
      result.fitting_pairs += std::abs(p.residual) <= options.fit_distance_m ? 1 : 0;
      const bool inlier = std::abs(p.residual) <= options.huber_k * state.sigma;
      inliers += inlier ? 1 : 0;
      const Eigen::Vector3d J = jacobian(p, state.t);
      if (inlier) H.noalias() += J * J.transpose();
    }
    result.rms_m = std::sqrt(sum2 / static_cast<double>(pairs.size()));
    result.inlier_share = static_cast<double>(inliers) / static_cast<double>(pairs.size());
    // Gauss-Newton covariance sigma^2 H^-1 of the inliers; the increment is the pose's own
    // change (it turns about t), so this is the covariance of (x, y, theta).
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(H);
    if (inliers >= 3 && lu.isInvertible()) {
      result.covariance = state.sigma * state.sigma * lu.inverse();
    }
  }
  result.scale_m = state.sigma;
}

/// The robust iteration (seed 004 eq. (5)-(7)) of `src` against `model` from `initial`.
IcpResult solve(const Model& model, const std::vector<Eigen::Vector2d>& src, const Pose2& initial,
                const IcpOptions& options) {
  IcpResult result;
  // Unknown until the final pairs say otherwise: infinite variances, no correlation.
  result.covariance = unconstrained();
  IcpState state;
  state.theta = initial.theta;
  state.t = Eigen::Vector2d(initial.x, initial.y);
  state.sigma = options.min_scale_m;
  iterate(model, src, state, options, result);
  final_fit(model, src, state, options, result);
  return result;
}

}  // namespace

IcpResult match_scans(const std::vector<Eigen::Vector2d>& reference,
                      const std::vector<Eigen::Vector2d>& current, const Pose2& initial,
                      const IcpOptions& options) {
  validate(options);
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
  check_pose(initial, "match_scans");

  // Reference: points in segments of >= 2 points carry a tangent (seed 004 eq. (3)).
  const auto ref_segments =
      segment_scan(reference, options.gap_m, options.resolution_m, options.breakpoint_angle_rad);
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
  const detail::PointBuckets buckets(reference, usable, options.max_correspondence_m);
  const std::vector<Eigen::Vector2d> normals =
      options.tangent_points > 2 ? fitted_normals(reference, ref_segments, options.tangent_points)
                                 : std::vector<Eigen::Vector2d>{};
  // Seed 004 puts the control points on the previous curve and the tangents on the current
  // one; here the roles are swapped so the result is directly the pose of `current` in the
  // reference frame (the same problem, with the tangents on the scan we index once).
  const Model model{reference, buckets, &segment_of, normals.empty() ? nullptr : &normals};
  return solve(model, matching_points(current, options, "match_scans"), initial, options);
}

IcpResult match_scan_to_map(const MapContour& contour, const std::vector<Eigen::Vector2d>& scan,
                            const Pose2& initial, const IcpOptions& options) {
  validate(options);
  if (scan.size() < 3) {
    throw Error("match_scan_to_map: scan has " + std::to_string(scan.size()) +
                " points, needs at least 3");
  }
  check_points(scan, "current");
  check_pose(initial, "match_scan_to_map");
  if (contour.size() < 3) {
    throw Error("match_scan_to_map: the map has " + std::to_string(contour.size()) +
                " contour points with a normal, needs at least 3");
  }
  const Model model{contour.points(), contour.buckets(), nullptr, &contour.normals()};
  return solve(model, matching_points(scan, options, "match_scan_to_map"), initial, options);
}

}  // namespace gridloc
