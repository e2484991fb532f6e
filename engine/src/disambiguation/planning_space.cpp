#include "gridloc/engine/disambiguation/planning_space.hpp"

#include "gridloc/engine/disambiguation/information.hpp"

namespace gridloc {

double PlanningSpace::info(const std::vector<Pose2>& hypotheses, const Eigen::Vector2d& r) const {
  return expected_eliminations(class_sizes(classes(hypotheses, r)));  // seed 002 §IV-A
}

}  // namespace gridloc
