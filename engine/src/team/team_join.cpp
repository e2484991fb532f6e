// Table I's intersection of pairs' solutions, generalized to slides: a partial solution places
// some robots (and may slide); a pair's solution for the next link must put the shared robot
// where the partial does, and then places the new robot.
#include <cmath>

#include "gridloc/engine/team/team_localization.hpp"
#include "gridloc/grids/error.hpp"
#include "wall_geometry.hpp"

namespace gridloc {

namespace {

Eigen::Vector2d position(const Pose2& pose) {
  return {pose.x, pose.y};
}

void move(Pose2& pose, const Eigen::Vector2d& shift) {
  pose.x += shift.x();
  pose.y += shift.y();
}

/// Where the shared robot ends up when the partial (at `placed`, sliding by `partial_slide`)
/// and the pair (at `paired`, sliding by `pair_slide`) agree, as the partial's shift along its
/// slide and what is left of the slides; nothing when they cannot agree within tolerance.
struct Agreement {
  double partial_shift = 0.0;
  Eigen::Vector2d shared = Eigen::Vector2d::Zero();
  Slide slide;  ///< length 0: fixed
};

std::optional<Agreement> agree_fixed(const Eigen::Vector2d& placed, const Eigen::Vector2d& paired,
                                     double tolerance) {
  if ((placed - paired).norm() > tolerance) return std::nullopt;
  return Agreement{0.0, placed, Slide{}};
}

/// A point sliding from `start` along `slide` meets a fixed point: where along it.
std::optional<double> pin(const Eigen::Vector2d& start, const Slide& slide,
                          const Eigen::Vector2d& point, double tolerance) {
  const double t = std::clamp((point - start).dot(slide.direction), 0.0, slide.length);
  if ((start + t * slide.direction - point).norm() > tolerance) return std::nullopt;
  return t;
}

std::optional<Agreement> agree_both_sliding(const Eigen::Vector2d& placed, const Slide& partial,
                                            const Eigen::Vector2d& paired, const Slide& pair,
                                            double tolerance) {
  const double turn = cross(partial.direction, pair.direction);
  const Eigen::Vector2d gap = paired - placed;
  if (std::abs(turn) > 1e-6) {  // crossing stretches: one meeting point
    const double t = std::clamp(cross(gap, pair.direction) / turn, 0.0, partial.length);
    const Eigen::Vector2d point = placed + t * partial.direction;
    if (!pin(paired, pair, point, tolerance)) return std::nullopt;
    return Agreement{t, point, Slide{}};
  }
  if (std::abs(cross(partial.direction, gap)) > tolerance) return std::nullopt;
  const double along = gap.dot(partial.direction);
  const double sign = partial.direction.dot(pair.direction) > 0.0 ? 1.0 : -1.0;
  const double first = std::max(0.0, along + std::min(0.0, sign * pair.length));
  const double last = std::min(partial.length, along + std::max(0.0, sign * pair.length));
  if (last < first - tolerance) return std::nullopt;
  const double start = std::min(first, partial.length);
  Agreement agreement{start, placed + start * partial.direction, Slide{}};
  if (last > start) agreement.slide = Slide{partial.direction, last - start};
  return agreement;
}

std::optional<Agreement> agree(const TeamSolution& partial, int shared, const Pose2& paired,
                               const Slide& pair_slide, double merge_m, double merge_theta) {
  if (std::abs(normalize_angle(partial.poses[shared].theta - paired.theta)) > merge_theta)
    return std::nullopt;
  const Eigen::Vector2d placed = position(partial.poses[shared]), other = position(paired);
  if (partial.slide.moving() && pair_slide.moving())
    return agree_both_sliding(placed, partial.slide, other, pair_slide, merge_m);
  if (partial.slide.moving()) {
    const auto t = pin(placed, partial.slide, other, merge_m);
    if (!t) return std::nullopt;
    return Agreement{*t, placed + *t * partial.slide.direction, Slide{}};
  }
  if (pair_slide.moving()) {
    if (!pin(other, pair_slide, placed, merge_m)) return std::nullopt;
    return Agreement{0.0, placed, Slide{}};
  }
  return agree_fixed(placed, other, merge_m);
}

TeamSolution first_pair(int robots, const LinkSolutions& link, const PairSolution& pair) {
  TeamSolution solution;
  solution.poses.assign(robots, Pose2{});
  solution.candidates.assign(robots, -1);
  solution.poses[link.from] = pair.from;
  solution.poses[link.to] = pair.to;
  solution.candidates[link.from] = pair.candidate_from;
  solution.candidates[link.to] = pair.candidate_to;
  solution.slide = pair.slide;
  solution.residual_m = pair.residual_m;
  return solution;
}

/// The partial extended by one pair solution, the link's `shared` robot already placed.
std::optional<TeamSolution> extend(const TeamSolution& partial, const std::vector<bool>& placed,
                                   const LinkSolutions& link, const PairSolution& pair,
                                   double merge_m, double merge_theta) {
  const bool shared_is_from = placed[link.from];
  const int shared = shared_is_from ? link.from : link.to;
  const int added = shared_is_from ? link.to : link.from;
  const Pose2& paired_shared = shared_is_from ? pair.from : pair.to;
  const int shared_candidate = shared_is_from ? pair.candidate_from : pair.candidate_to;
  if (partial.candidates[shared] >= 0 && shared_candidate >= 0 &&
      partial.candidates[shared] != shared_candidate)
    return std::nullopt;
  const auto agreement = agree(partial, shared, paired_shared, pair.slide, merge_m, merge_theta);
  if (!agreement) return std::nullopt;
  TeamSolution next = partial;
  if (partial.slide.moving())
    for (std::size_t r = 0; r < placed.size(); ++r)
      if (placed[r]) move(next.poses[r], agreement->partial_shift * partial.slide.direction);
  next.slide = agreement->slide;
  Pose2 added_pose = shared_is_from ? pair.to : pair.from;
  move(added_pose, agreement->shared - position(paired_shared));
  next.poses[added] = added_pose;
  next.candidates[added] = shared_is_from ? pair.candidate_to : pair.candidate_from;
  next.residual_m = std::max(partial.residual_m, pair.residual_m);
  return next;
}

}  // namespace

std::vector<TeamSolution> join_pair_solutions(int robots, const std::vector<LinkSolutions>& chain,
                                              double merge_m, double merge_theta,
                                              std::size_t max_partial, bool* truncated) {
  if (truncated) *truncated = false;
  if (chain.empty()) return {};
  std::vector<bool> placed(robots, false);
  std::vector<TeamSolution> partials;
  for (const PairSolution& pair : chain.front().solutions)
    partials.push_back(first_pair(robots, chain.front(), pair));
  placed[chain.front().from] = placed[chain.front().to] = true;
  for (std::size_t k = 1; k < chain.size(); ++k) {
    const LinkSolutions& link = chain[k];
    if (placed[link.from] == placed[link.to])
      throw Error("join_pair_solutions: link " + std::to_string(link.from) + "-" +
                  std::to_string(link.to) + " must share exactly one robot with those before");
    std::vector<TeamSolution> next;
    for (const TeamSolution& partial : partials)
      for (const PairSolution& pair : link.solutions) {
        if (next.size() >= max_partial) {
          if (truncated) *truncated = true;
          break;
        }
        if (auto extended = extend(partial, placed, link, pair, merge_m, merge_theta))
          next.push_back(std::move(*extended));
      }
    partials = std::move(next);
    placed[link.from] = placed[link.to] = true;
  }
  return partials;
}

}  // namespace gridloc
