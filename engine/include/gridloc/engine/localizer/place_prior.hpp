#pragma once
/// What the odometry says of where a tracked place can be (issue 34): a place carried by the
/// odometry lies at the carried pose with the grown covariance, so a pose the window finds
/// farther away is less likely before the scan is read. A window's candidates are ranked by
/// the scan's evidence plus this log prior, as a particle filter weighs a particle drawn
/// from its motion model: a corridor turned round or slid along scores as well as the track,
/// but lies where the odometry did not go.
#include <Eigen/Core>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// A look-alike a wide window holds besides its chosen place, and how much less likely the
/// odometry makes it than the chosen one (log prior, <= 0 when farther from the carried pose).
struct LookAlike {
  Pose2 pose;
  double log_prior = 0.0;
};

/// -1/2 the squared Mahalanobis distance of `pose` from `carried` under `covariance` (x, y,
/// heading; the heading difference wrapped to [-pi, pi]). `floor` (variances of x, y and
/// heading) is added to the covariance's diagonal so a tight or singular one still ranks.
double log_prior(const Pose2& pose, const Pose2& carried, const Eigen::Matrix3d& covariance,
                 const Eigen::Vector3d& floor);

}  // namespace gridloc
