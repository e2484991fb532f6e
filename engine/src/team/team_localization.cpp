#include "gridloc/engine/team/team_localization.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"
#include "team_checks.hpp"
#include "wall_geometry.hpp"

namespace gridloc {

void validate(const TeamOptions& options) {
  validate(options.camera);
  validate(options.gate);
  constexpr const char* kOwner = "team options";
  require_positive(options.merge_m, kOwner, "merge_m");
  require_positive(options.merge_theta, kOwner, "merge_theta");
  require_option(options.rival_ratio > 0.0 && options.rival_ratio <= 1.0, kOwner, "rival_ratio",
                 options.rival_ratio, "must lie in (0, 1]");
  require_share(options.min_agreement, kOwner, "min_agreement");
  require_positive(options.agreement_tolerance_m, kOwner, "agreement_tolerance_m");
  require_option(options.max_partial >= 1, kOwner, "max_partial",
                 static_cast<double>(options.max_partial), "must be >= 1");
}

namespace {

void check_inputs(const std::vector<TeamRobot>& robots, const std::vector<VirtualLink>& links,
                  const TeamOptions& options) {
  validate(options);
  const int count = static_cast<int>(robots.size());
  for (const VirtualLink& link : links) validate(link, count, options.camera);
  const bool any = std::any_of(robots.begin(), robots.end(),
                               [](const TeamRobot& robot) { return !robot.candidates.empty(); });
  if (!any) throw Error("no robot has a candidate placement: no scan showed a corner or wall");
}

/// A robot that saw no feature, placed where the link puts it from the other robot's
/// candidate (its heading from the link's back bearing).
std::optional<PoseCandidate> placed_by_link(const VirtualLink& link, const PoseCandidate& known,
                                            bool known_is_from) {
  if (std::isnan(link.back_bearing)) return std::nullopt;
  PoseCandidate placed = known;
  placed.weight = 0.0;
  placed.feature = placed.map_feature = -1;
  if (known_is_from) {
    const Eigen::Vector2d p = linked_position(link, known.pose);
    placed.pose = {p.x(), p.y(), linked_heading(link, known.pose.theta)};
  } else {
    // known = to: theta_from = theta_to - (bearing - back_bearing + pi).
    const double from_heading = normalize_angle(known.pose.theta - (linked_heading(link, 0.0)));
    const Eigen::Vector2d p =
        known.position() - link.length_m * team_detail::unit_at(from_heading + link.bearing);
    placed.pose = {p.x(), p.y(), from_heading};
  }
  return placed;
}

/// A link's pair solutions; a robot without candidates takes the other's, moved by the link.
LinkSolutions pair_solutions(const VirtualLink& link, const std::vector<TeamRobot>& robots,
                             const MapFeatures& map, const TeamOptions& options) {
  const auto& from = robots[link.from].candidates;
  const auto& to = robots[link.to].candidates;
  LinkSolutions result{link.from, link.to, {}};
  if (!from.empty() && !to.empty()) {
    result.solutions = localize_pair(from, to, link, map, options.camera, options.gate);
    return result;
  }
  if (from.empty() && to.empty())
    throw Error("robots " + std::to_string(link.from) + " and " + std::to_string(link.to) +
                " both saw no corner or wall: link each to a robot that did");
  const bool known_is_from = !from.empty();
  const auto& known = known_is_from ? from : to;
  for (std::size_t c = 0; c < known.size(); ++c) {
    const auto other = placed_by_link(link, known[c], known_is_from);
    if (!other) continue;
    PairSolution solution;
    solution.candidate_from = known_is_from ? static_cast<int>(c) : -1;
    solution.candidate_to = known_is_from ? -1 : static_cast<int>(c);
    solution.from = known_is_from ? known[c].pose : other->pose;
    solution.to = known_is_from ? other->pose : known[c].pose;
    if (known[c].segment()) solution.slide = Slide{known[c].along, known[c].length};
    result.solutions.push_back(solution);
  }
  return result;
}

/// One robot alone: each candidate is a solution.
std::vector<TeamSolution> single_robot(const TeamRobot& robot) {
  std::vector<TeamSolution> solutions;
  for (std::size_t c = 0; c < robot.candidates.size(); ++c) {
    const PoseCandidate& candidate = robot.candidates[c];
    TeamSolution solution{{candidate.pose}, {static_cast<int>(c)}, Slide{}, 0.0, 0.0};
    if (candidate.segment()) solution.slide = Slide{candidate.along, candidate.length};
    solutions.push_back(solution);
  }
  return solutions;
}

std::vector<int> links_left_over(std::size_t links, const std::vector<int>& tree) {
  std::vector<int> checks;
  for (int l = 0; l < static_cast<int>(links); ++l)
    if (std::find(tree.begin(), tree.end(), l) == tree.end()) checks.push_back(l);
  return checks;
}

}  // namespace

TeamAnswer localize_team(const std::vector<TeamRobot>& robots,
                         const std::vector<VirtualLink>& links, const MapFeatures& map,
                         const TeamOptions& options) {
  check_inputs(robots, links, options);
  const int count = static_cast<int>(robots.size());
  const std::vector<int> tree = choose_links(count, links);
  std::vector<LinkSolutions> chain;
  chain.reserve(tree.size());
  for (int l : tree) chain.push_back(pair_solutions(links[l], robots, map, options));
  bool truncated = false;
  std::vector<TeamSolution> solutions =
      count == 1 ? single_robot(robots.front())
                 : join_pair_solutions(count, chain, options.merge_m, options.merge_theta,
                                       options.max_partial, &truncated);
  const std::vector<int> checks = links_left_over(links.size(), tree);
  solutions = team_detail::agreeing_with_links(std::move(solutions), links, checks, map, options);
  // Refit first: joining pairs moves a robot rigidly with its pair, off its own wall by the
  // links' error; the fit puts it back before its scan is checked.
  if (options.refine) team_detail::refine(solutions, robots, links, options);
  solutions = team_detail::agreeing_with_scans(std::move(solutions), robots, map, options);
  TeamAnswer answer = team_detail::answer_from(
      team_detail::ranked_rivals(std::move(solutions), robots, options), robots, map, options);
  answer.links_used = tree;
  answer.links_used.insert(answer.links_used.end(), checks.begin(), checks.end());
  answer.truncated = truncated;
  return answer;
}

}  // namespace gridloc
