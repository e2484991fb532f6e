// The odometry's prior on where a carried place lies.
#include "gridloc/engine/localizer/place_prior.hpp"

#include <Eigen/Cholesky>

namespace gridloc {

double log_prior(const Pose2& pose, const Pose2& carried, const Eigen::Matrix3d& covariance,
                 const Eigen::Vector3d& floor) {
  const Eigen::Vector3d offset(pose.x - carried.x, pose.y - carried.y,
                               normalize_angle(pose.theta - carried.theta));
  Eigen::Matrix3d regularized = covariance;
  regularized.diagonal() += floor;
  const Eigen::LDLT<Eigen::Matrix3d> factor(regularized);
  return -0.5 * offset.dot(factor.solve(offset));
}

}  // namespace gridloc
