#pragma once
/// The yardstick beside every seed 002 figure: no localizing path can be shorter than the way
/// (inside OI) from the start to the nearest point where sensing rules out at least one
/// hypothesis. With two hypotheses any such point resolves them, so the bound is then the
/// optimum itself. Both are taken on a fine lattice over OI.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "gridloc/engine/disambiguation/planning_space.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

struct TravelBound {
  /// The shortest path inside OI from the start to the nearest informative lattice point;
  /// +infinity when no lattice point is informative.
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< that point (start frame)
  double step = 0.0;                                ///< the lattice spacing used
  int points = 0;                                   ///< lattice points inside OI
  bool optimal = false;  ///< two hypotheses: the bound is the shortest localizing path
};

/// The bound for the hypotheses (at least two) on a lattice of spacing `step` (0: about 4000
/// points over OI, and at most `max_step`: a quarter of a limited range, say). Throws
/// gridloc::Error for fewer than two hypotheses or a bad step.
TravelBound travel_lower_bound(const PlanningSpace& space, const std::vector<Pose2>& hypotheses,
                               double step = 0.0,
                               double max_step = std::numeric_limits<double>::infinity());

}  // namespace gridloc
