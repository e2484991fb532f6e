#pragma once
/// Team localization (seed 003 ch. IV): n linked robots localized together. Links are chosen
/// for the shortest maximum length (a minimum spanning tree of the measured links: the
/// camera's error grows quickly with length), pairs are localized along them and the pairs'
/// solutions intersected on their shared robots (Table I); the links left over check each
/// solution and, with the features, average out the error. The same solver serves the
/// thesis's feature placements (every candidate weight 1) and any estimator's weighted
/// hypotheses: the answer is the consistent assignment of highest total weight.
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "gridloc/engine/estimate.hpp"
#include "gridloc/engine/team/pair_localization.hpp"

namespace gridloc {

/// One robot of the team: its candidates (from its features or from an estimator) and, when
/// known, its scan, against which every solution's pose for it is checked. A robot with no
/// candidate (its scan showed no feature) is placed by its links alone when they carry a back
/// bearing.
struct TeamRobot {
  std::vector<PoseCandidate> candidates;
  RangeScan scan;  ///< empty ranges: no scan check
};

/// One pose per robot. With a slide, every pose may move along it together.
struct TeamSolution {
  std::vector<Pose2> poses;
  std::vector<int> candidates;  ///< each robot's candidate index (-1: placed by a link)
  Slide slide;                  ///< length 0: fixed
  double weight = 0.0;          ///< the candidates' weights summed (localize_team)
  double residual_m = 0.0;      ///< the largest link residual
};

struct TeamOptions {
  CameraModel camera;
  LinkGateOptions gate;
  /// Solutions whose poses all lie this close are one (m, rad); also the tolerance with
  /// which two pairs' solutions must agree on their shared robot.
  double merge_m = 0.05;
  double merge_theta = 0.0872664625997;  ///< 5 deg
  /// Solutions of at least this share of the best total weight are rivals: with one the
  /// team is ambiguous (equal weights, as the thesis's placements, always are).
  double rival_ratio = 0.95;
  /// A solution's pose for a robot with a scan must agree with it (scan_agreement() >= this
  /// at agreement_tolerance_m); 0 skips the check (the thesis's method).
  double min_agreement = 0.8;
  double agreement_tolerance_m = 0.03;
  bool refine = true;  ///< average the poses over all links used (ch. III D)
  /// Most partial solutions kept while joining pairs; beyond, the answer says truncated.
  std::size_t max_partial = 20000;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const TeamOptions& options);

struct RobotAnswer {
  Verdict verdict = Verdict::NotLocalized;
  Pose2 pose;                 ///< in the best solution
  std::vector<Pose2> places;  ///< its distinct poses over the rival solutions, best first
  bool slides = false;        ///< a rival solution lets it slide along a wall
};

struct TeamAnswer {
  /// Localized: one solution, fixed; ambiguous: rivals or a slide, or (on map features that
  /// are not exact) a solution resting on a feature placement, which could have missed the
  /// true place; not localized: none.
  Verdict verdict = Verdict::NotLocalized;
  std::vector<TeamSolution> solutions;  ///< the rivals, best first
  std::vector<RobotAnswer> robots;
  std::vector<int> links_used;  ///< indices into the links: the tree, then the checks
  /// Robot pairs (i < j) a rival solution puts each where the best puts the other.
  std::vector<std::pair<int, int>> swaps;
  bool truncated = false;  ///< max_partial was reached: rivals may be missing
  bool unique() const { return verdict == Verdict::Localized; }
};

/// Localizes the team; throws gridloc::Error for a link validate() refuses, no candidate at
/// all, or robots the links do not join into one team (naming a robot with no link to the
/// first robot's group).
TeamAnswer localize_team(const std::vector<TeamRobot>& robots,
                         const std::vector<VirtualLink>& links, const MapFeatures& map,
                         const TeamOptions& options = {});

/// The links chosen for the shortest maximum link: a spanning tree of the team's link graph,
/// in join order (each link after the first adds one robot), starting from the shortest link.
/// Throws gridloc::Error naming a robot no link joins to the rest.
std::vector<int> choose_links(int robots, const std::vector<VirtualLink>& links);

/// One link's pair solutions, from robot `from` to robot `to`.
struct LinkSolutions {
  int from = 0, to = 1;
  std::vector<PairSolution> solutions;
};

/// Intersects pairs' solutions on their shared robots (ch. IV C, Table I): links in join
/// order, each after the first sharing one robot with those before; two pairs agree where
/// they put the shared robot within merge_m and merge_theta (slides pinned or shortened to
/// agree). At most max_partial results (truncated set when reached).
std::vector<TeamSolution> join_pair_solutions(int robots, const std::vector<LinkSolutions>& chain,
                                              double merge_m, double merge_theta,
                                              std::size_t max_partial, bool* truncated = nullptr);

}  // namespace gridloc
