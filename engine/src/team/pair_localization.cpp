#include "gridloc/engine/team/pair_localization.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "wall_geometry.hpp"

namespace gridloc {

void validate(const LinkGateOptions& options) {
  constexpr const char* kOwner = "link gate options";
  require_non_negative(options.placement_sigma_m, kOwner, "placement_sigma_m");
  require_non_negative(options.heading_sigma, kOwner, "heading_sigma");
  require_positive(options.gate_sigmas, kOwner, "gate_sigmas");
}

double position_gate(const VirtualLink& link, const CameraModel& camera,
                     const LinkGateOptions& options) {
  const double lever = link.length_m * std::hypot(camera.bearing_sigma, options.heading_sigma);
  const double length = length_sigma(camera, link.length_m);
  const double placement2 = 2.0 * options.placement_sigma_m * options.placement_sigma_m;
  return options.gate_sigmas * std::sqrt(placement2 + length * length + lever * lever) + 1e-9;
}

double heading_gate(const CameraModel& camera, const LinkGateOptions& options) {
  return options.gate_sigmas * std::sqrt(2.0 * options.heading_sigma * options.heading_sigma +
                                         2.0 * camera.bearing_sigma * camera.bearing_sigma) +
         1e-9;
}

namespace {

/// Where along the two candidates (s on from's, r on to's) the link's equation
/// from(s) + v = to(r) is best met, i.e. s * u_from - r * u_to = g with g = to(0) - from(0) - v.
struct LinkFit {
  double s = 0.0, r = 0.0;
  double residual = 0.0;
  Slide
      slide;  ///< length 0: fixed  ///< the stretch of s over which the fit holds (parallel walls)
};

double fit_residual(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g,
                    double s, double r) {
  return (s * a.along - r * b.along - g).norm();
}

/// The best s for a given r (and r for a given s), clamped to the candidates' lengths.
double best_s(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g, double r) {
  return std::clamp((g + r * b.along).dot(a.along), 0.0, a.length);
}
double best_r(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g, double s) {
  return std::clamp((s * a.along - g).dot(b.along), 0.0, b.length);
}

LinkFit fit_crossing(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g) {
  const double denominator = cross(a.along, b.along);
  LinkFit fit;
  fit.s = std::clamp(cross(g, b.along) / denominator, 0.0, a.length);
  fit.r = best_r(a, b, g, fit.s);
  fit.s = best_s(a, b, g, fit.r);
  fit.residual = fit_residual(a, b, g, fit.s, fit.r);
  return fit;
}

/// Parallel walls: s - sign * r = g . u_from for every r along to's candidate.
LinkFit fit_parallel(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g) {
  const double sign = a.along.dot(b.along) > 0.0 ? 1.0 : -1.0;
  const double c = g.dot(a.along);
  const double lowest = c + std::min(0.0, sign * b.length);
  const double highest = c + std::max(0.0, sign * b.length);
  LinkFit fit;
  const double first = std::max(lowest, 0.0), last = std::min(highest, a.length);
  fit.s = last >= first ? first : (highest < 0.0 ? 0.0 : a.length);
  fit.r = best_r(a, b, g, fit.s);
  fit.residual = fit_residual(a, b, g, fit.s, fit.r);
  if (last > first) fit.slide = Slide{a.along, last - first};
  return fit;
}

LinkFit fit_link(const PoseCandidate& a, const PoseCandidate& b, const Eigen::Vector2d& g) {
  LinkFit fit;
  if (a.segment() && b.segment()) {
    if (std::abs(cross(a.along, b.along)) > 1e-6) return fit_crossing(a, b, g);
    return fit_parallel(a, b, g);
  }
  if (a.segment()) fit.s = best_s(a, b, g, 0.0);
  if (b.segment()) fit.r = best_r(a, b, g, 0.0);
  fit.residual = fit_residual(a, b, g, fit.s, fit.r);
  return fit;
}

Pose2 at(const PoseCandidate& candidate, double t) {
  const Eigen::Vector2d p = candidate.position(t);
  return {p.x(), p.y(), candidate.pose.theta};
}

}  // namespace

std::vector<PairSolution> localize_pair(const std::vector<PoseCandidate>& from_candidates,
                                        const std::vector<PoseCandidate>& to_candidates,
                                        const VirtualLink& link, const MapFeatures& map,
                                        const CameraModel& camera, const LinkGateOptions& options) {
  validate(options);
  const double gate = position_gate(link, camera, options);
  const double turn_gate = heading_gate(camera, options);
  std::vector<PairSolution> solutions;
  for (std::size_t i = 0; i < from_candidates.size(); ++i) {
    const PoseCandidate& a = from_candidates[i];
    const Eigen::Vector2d v = linked_position(link, a.pose) - a.position();
    const double expected_heading = linked_heading(link, a.pose.theta);
    for (std::size_t j = 0; j < to_candidates.size(); ++j) {
      const PoseCandidate& b = to_candidates[j];
      if (!std::isnan(expected_heading) &&
          std::abs(normalize_angle(expected_heading - b.pose.theta)) > turn_gate)
        continue;
      const LinkFit fit = fit_link(a, b, b.position() - a.position() - v);
      if (fit.residual > gate) continue;
      PairSolution solution{static_cast<int>(i), static_cast<int>(j), at(a, fit.s),
                            at(b, fit.r),        fit.slide,           fit.residual,
                            a.weight + b.weight};
      const double middle = fit.slide.moving() ? 0.5 * fit.slide.length : 0.0;
      const Eigen::Vector2d shift = fit.slide.moving()
                                        ? Eigen::Vector2d(middle * fit.slide.direction)
                                        : Eigen::Vector2d::Zero();
      if (!line_of_sight(map, Eigen::Vector2d(solution.from.x, solution.from.y) + shift,
                         Eigen::Vector2d(solution.to.x, solution.to.y) + shift))
        continue;
      solutions.push_back(solution);
    }
  }
  std::stable_sort(
      solutions.begin(), solutions.end(),
      [](const PairSolution& x, const PairSolution& y) { return x.residual_m < y.residual_m; });
  return solutions;
}

}  // namespace gridloc
