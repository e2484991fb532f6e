#include "team_checks.hpp"

#include <algorithm>
#include <cmath>

#include "wall_geometry.hpp"

namespace gridloc::team_detail {

namespace {

Eigen::Vector2d position(const Pose2& pose) {
  return {pose.x, pose.y};
}

Eigen::Vector2d slide_shift(const TeamSolution& solution, double t) {
  return solution.slide.moving() ? Eigen::Vector2d(t * solution.slide.direction)
                                 : Eigen::Vector2d::Zero();
}

bool link_agrees(const TeamSolution& solution, const VirtualLink& link, const MapFeatures& map,
                 const TeamOptions& options) {
  const Pose2& from = solution.poses[link.from];
  const Pose2& to = solution.poses[link.to];
  if ((linked_position(link, from) - position(to)).norm() >
      position_gate(link, options.camera, options.gate))
    return false;
  const double heading = linked_heading(link, from.theta);
  if (!std::isnan(heading) &&
      std::abs(normalize_angle(heading - to.theta)) > heading_gate(options.camera, options.gate))
    return false;
  const Eigen::Vector2d middle =
      slide_shift(solution, solution.slide.moving() ? 0.5 * solution.slide.length : 0.0);
  return line_of_sight(map, position(from) + middle, position(to) + middle);
}

/// Every robot in the free space, and its scan (when it has one) agreeing with the map there.
bool scans_agree(const TeamSolution& solution, const std::vector<TeamRobot>& robots,
                 const MapFeatures& map, const TeamOptions& options, double t) {
  const Eigen::Vector2d shift = slide_shift(solution, t);
  for (std::size_t r = 0; r < robots.size(); ++r) {
    Pose2 pose = solution.poses[r];
    pose.x += shift.x();
    pose.y += shift.y();
    if (!map.walls.empty() && !inside_free_space(map, position(pose))) return false;
    if (robots[r].scan.ranges.empty() || options.min_agreement <= 0.0) continue;
    if (scan_agreement(robots[r].scan, pose, map, options.agreement_tolerance_m) <
        options.min_agreement)
      return false;
  }
  return true;
}

/// The longest stretch of the slide along which every scan agrees, sampled every 2 cm.
std::optional<TeamSolution> agreeing_stretch(const TeamSolution& solution,
                                             const std::vector<TeamRobot>& robots,
                                             const MapFeatures& map, const TeamOptions& options) {
  const double length = solution.slide.length;
  const int samples = std::clamp(static_cast<int>(std::ceil(length / 0.02)), 1, 500);
  int best_first = -1, best_count = 0, first = -1;
  for (int k = 0; k <= samples + 1; ++k) {
    const bool ok =
        k <= samples && scans_agree(solution, robots, map, options, length * k / samples);
    if (ok && first < 0) first = k;
    if (!ok && first >= 0) {
      if (k - first > best_count) best_first = first, best_count = k - first;
      first = -1;
    }
  }
  if (best_count == 0) return std::nullopt;
  TeamSolution kept = solution;
  const Eigen::Vector2d shift = slide_shift(solution, length * best_first / samples);
  for (Pose2& pose : kept.poses) pose.x += shift.x(), pose.y += shift.y();
  const double kept_length = length * (best_count - 1) / samples;
  if (kept_length > 0.0)
    kept.slide.length = kept_length;
  else
    kept.slide = Slide{};
  return kept;
}

/// A position estimate and its weight (1 / variance).
struct Vote {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double weight = 0.0;
  void add(const Eigen::Vector2d& p, double w) { sum += w * p, weight += w; }
};

Eigen::Vector2d anchor(const PoseCandidate& candidate, const Eigen::Vector2d& current) {
  if (!candidate.segment()) return candidate.position();
  const double t =
      std::clamp((current - candidate.position()).dot(candidate.along), 0.0, candidate.length);
  return candidate.position(t);
}

/// A robot's heading as its candidate has it and as each link with a back bearing implies it
/// from the other robot's, averaged on the circle with weights 1 / variance.
double refined_heading(const TeamSolution& solution, std::size_t robot,
                       const std::vector<TeamRobot>& robots, const std::vector<VirtualLink>& links,
                       const TeamOptions& options) {
  const double own = std::max(options.gate.heading_sigma, 1e-4);
  const double bearing = options.camera.bearing_sigma;
  const double linked = 1.0 / (own * own + 2.0 * bearing * bearing);
  const int r = static_cast<int>(robot);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const int c = solution.candidates[robot];
  if (c >= 0) sum += team_detail::unit_at(robots[robot].candidates[c].pose.theta) / (own * own);
  for (const VirtualLink& link : links) {
    if (std::isnan(link.back_bearing) || (link.from != r && link.to != r)) continue;
    const double turn = linked_heading(link, 0.0);  // theta_to - theta_from
    const double heading = link.to == r ? solution.poses[link.from].theta + turn
                                        : solution.poses[link.to].theta - turn;
    sum += linked * team_detail::unit_at(heading);
  }
  return sum.squaredNorm() > 0.0 ? team_detail::heading_of(sum) : solution.poses[robot].theta;
}

/// A robot's position as its candidate has it and as each link puts it from the other robot,
/// averaged with weights 1 / variance.
Eigen::Vector2d refined_position(const TeamSolution& solution, std::size_t robot,
                                 const std::vector<TeamRobot>& robots,
                                 const std::vector<VirtualLink>& links,
                                 const TeamOptions& options) {
  const double placement = std::max(options.gate.placement_sigma_m, 1e-3);
  const int r = static_cast<int>(robot);
  Vote vote;
  const int c = solution.candidates[robot];
  const Eigen::Vector2d current = position(solution.poses[robot]);
  if (c >= 0) vote.add(anchor(robots[robot].candidates[c], current), 1.0 / (placement * placement));
  for (const VirtualLink& link : links) {
    if (link.from != r && link.to != r) continue;
    const double lever =
        link.length_m * std::hypot(options.camera.bearing_sigma, options.gate.heading_sigma);
    const double sigma = std::hypot(length_sigma(options.camera, link.length_m), lever);
    const Pose2& from = solution.poses[link.from];
    const Eigen::Vector2d vector = linked_position(link, from) - position(from);
    vote.add(link.to == r ? Eigen::Vector2d(position(from) + vector)
                          : Eigen::Vector2d(position(solution.poses[link.to]) - vector),
             1.0 / std::max(sigma * sigma, 1e-8));
  }
  return vote.weight > 0.0 ? Eigen::Vector2d(vote.sum / vote.weight) : current;
}

void refine_one(TeamSolution& solution, const std::vector<TeamRobot>& robots,
                const std::vector<VirtualLink>& links, const TeamOptions& options) {
  for (int iteration = 0; iteration < 20; ++iteration)
    for (std::size_t r = 0; r < robots.size(); ++r) {
      solution.poses[r].theta = refined_heading(solution, r, robots, links, options);
      const Eigen::Vector2d p = refined_position(solution, r, robots, links, options);
      solution.poses[r].x = p.x();
      solution.poses[r].y = p.y();
    }
}

bool same_solution(const TeamSolution& a, const TeamSolution& b, const TeamOptions& options) {
  if (a.slide.moving() != b.slide.moving()) return false;
  for (std::size_t r = 0; r < a.poses.size(); ++r) {
    if ((position(a.poses[r]) - position(b.poses[r])).norm() > options.merge_m) return false;
    if (std::abs(normalize_angle(a.poses[r].theta - b.poses[r].theta)) > options.merge_theta)
      return false;
  }
  return true;
}

bool near(const Pose2& a, const Pose2& b, const TeamOptions& options) {
  return (position(a) - position(b)).norm() <= options.merge_m &&
         std::abs(normalize_angle(a.theta - b.theta)) <= options.merge_theta;
}

}  // namespace

std::vector<TeamSolution> agreeing_with_links(std::vector<TeamSolution> solutions,
                                              const std::vector<VirtualLink>& links,
                                              const std::vector<int>& checks,
                                              const MapFeatures& map, const TeamOptions& options) {
  std::erase_if(solutions, [&](const TeamSolution& solution) {
    return std::any_of(checks.begin(), checks.end(),
                       [&](int l) { return !link_agrees(solution, links[l], map, options); });
  });
  return solutions;
}

std::vector<TeamSolution> agreeing_with_scans(std::vector<TeamSolution> solutions,
                                              const std::vector<TeamRobot>& robots,
                                              const MapFeatures& map, const TeamOptions& options) {
  std::vector<TeamSolution> kept;
  for (const TeamSolution& solution : solutions) {
    if (!solution.slide.moving()) {
      if (scans_agree(solution, robots, map, options, 0.0)) kept.push_back(solution);
    } else if (auto stretch = agreeing_stretch(solution, robots, map, options)) {
      kept.push_back(std::move(*stretch));
    }
  }
  return kept;
}

void refine(std::vector<TeamSolution>& solutions, const std::vector<TeamRobot>& robots,
            const std::vector<VirtualLink>& links, const TeamOptions& options) {
  for (TeamSolution& solution : solutions)
    if (!solution.slide.moving()) refine_one(solution, robots, links, options);
}

std::vector<TeamSolution> ranked_rivals(std::vector<TeamSolution> solutions,
                                        const std::vector<TeamRobot>& robots,
                                        const TeamOptions& options) {
  for (TeamSolution& solution : solutions) {
    solution.weight = 0.0;
    for (std::size_t r = 0; r < robots.size(); ++r)
      if (solution.candidates[r] >= 0)
        solution.weight += robots[r].candidates[solution.candidates[r]].weight;
  }
  std::stable_sort(solutions.begin(), solutions.end(), [](const auto& a, const auto& b) {
    if (a.weight != b.weight) return a.weight > b.weight;
    return a.residual_m < b.residual_m;
  });
  std::vector<TeamSolution> rivals;
  for (TeamSolution& solution : solutions) {
    if (!rivals.empty() && solution.weight < options.rival_ratio * rivals.front().weight - 1e-12)
      break;
    const bool duplicate = std::any_of(rivals.begin(), rivals.end(), [&](const auto& kept) {
      return same_solution(kept, solution, options);
    });
    if (!duplicate) rivals.push_back(std::move(solution));
  }
  return rivals;
}

/// Robot pairs (i < j) a rival puts each where the best puts the other.
std::vector<std::pair<int, int>> swaps_of(const std::vector<TeamSolution>& solutions,
                                          const TeamOptions& options) {
  std::vector<std::pair<int, int>> swaps;
  const auto& best = solutions.front().poses;
  const auto close = [&](const Pose2& a, const Pose2& b) {
    return (position(a) - position(b)).norm() <= 2.0 * options.merge_m;
  };
  for (std::size_t k = 1; k < solutions.size(); ++k)
    for (std::size_t i = 0; i < best.size(); ++i)
      for (std::size_t j = i + 1; j < best.size(); ++j) {
        const auto& rival = solutions[k].poses;
        const std::pair<int, int> pair{static_cast<int>(i), static_cast<int>(j)};
        if (close(rival[i], best[j]) && close(rival[j], best[i]) &&
            std::find(swaps.begin(), swaps.end(), pair) == swaps.end())
          swaps.push_back(pair);
      }
  return swaps;
}

/// Whether the solution places a robot by one of its scan's features (not by an estimator's
/// hypothesis or a link alone).
bool rests_on_a_feature(const TeamSolution& solution, const std::vector<TeamRobot>& robots) {
  for (std::size_t r = 0; r < robots.size(); ++r) {
    const int c = solution.candidates[r];
    if (c >= 0 && robots[r].candidates[c].feature >= 0) return true;
  }
  return false;
}

TeamAnswer answer_from(std::vector<TeamSolution> rivals, const std::vector<TeamRobot>& team,
                       const MapFeatures& map, const TeamOptions& options) {
  const int robots = static_cast<int>(team.size());
  TeamAnswer answer;
  answer.robots.resize(robots);
  answer.solutions = std::move(rivals);
  if (answer.solutions.empty()) return answer;
  const bool fixed = !answer.solutions.front().slide.moving();
  const bool trusted = map.exact || !rests_on_a_feature(answer.solutions.front(), team);
  answer.verdict =
      answer.solutions.size() == 1 && fixed && trusted ? Verdict::Localized : Verdict::Ambiguous;
  for (int r = 0; r < robots; ++r) {
    RobotAnswer& robot = answer.robots[r];
    robot.pose = answer.solutions.front().poses[r];
    for (const TeamSolution& solution : answer.solutions) {
      robot.slides = robot.slides || solution.slide.moving();
      const Pose2& pose = solution.poses[r];
      if (std::none_of(robot.places.begin(), robot.places.end(),
                       [&](const Pose2& place) { return near(place, pose, options); }))
        robot.places.push_back(pose);
    }
    robot.verdict = robot.places.size() == 1 && !robot.slides && trusted ? Verdict::Localized
                                                                         : Verdict::Ambiguous;
  }
  answer.swaps = swaps_of(answer.solutions, options);
  return answer;
}

}  // namespace gridloc::team_detail
