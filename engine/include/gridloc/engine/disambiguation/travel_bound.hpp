#pragma once
/// The yardsticks beside every seed 002 figure, taken on a fine lattice over OI:
/// - no localizing path is shorter than the way (inside OI) from the start to the nearest
///   point where sensing rules out at least one hypothesis (with two hypotheses any such
///   point resolves them: the bound is then the optimum itself);
/// - when the truth is known (simulation), none is shorter than, for every wrong hypothesis,
///   the way to the nearest point that tells it from the truth, measured inside the OI of that
///   pair (until then their views agree, so the robot stayed where both maps are free): the
///   largest of these is a tighter bound for three hypotheses and more.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "gridloc/engine/disambiguation/planning_space.hpp"

namespace gridloc {

struct TravelBound {
  /// The shortest path inside OI from the start to the nearest informative lattice point;
  /// +infinity when no lattice point is informative.
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< that point (start frame)
  /// With the truth known: the largest, over the wrong hypotheses, of the way inside the
  /// pair's OI to the nearest lattice point where that hypothesis and the truth differ
  /// (+infinity when one never does; NaN without the truth).
  double pairwise = std::numeric_limits<double>::quiet_NaN();
  double step = 0.0;     ///< the lattice spacing used
  int points = 0;        ///< lattice points inside OI
  bool optimal = false;  ///< two hypotheses: `distance` is the shortest localizing path
};

/// The bounds for the hypotheses (at least two) on a lattice of spacing `step` (0: about
/// 4000 points over OI, and at most `max_step`: a quarter of a limited range, say);
/// `truth` the index of the true hypothesis, or -1. Throws gridloc::Error for fewer than two
/// hypotheses, a bad step or a truth index out of range.
TravelBound travel_lower_bound(const PlanningSpace& space, const std::vector<Pose2>& hypotheses,
                               int truth = -1, double step = 0.0,
                               double max_step = std::numeric_limits<double>::infinity());

}  // namespace gridloc
