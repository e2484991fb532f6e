#pragma once
/// Virtual links (seed 003 ch. III C-D, appendix A): what a robot's rotating camera measures of
/// another robot, the distance between their centres and the bearing at which it sees it,
/// with the camera's error model and the line of sight it needs.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "gridloc/engine/team/map_features.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// A measured link from robot `from` to robot `to`.
struct VirtualLink {
  int from = 0, to = 1;
  double length_m = 0.0;  ///< distance between the robots' centres
  /// The bearing of `to` seen from `from`, CCW from from's heading (rad; the thesis's phi).
  double bearing = 0.0;
  /// The bearing of `from` seen from `to` (rad), when to's camera measured it; NaN otherwise.
  /// With it the relative heading theta_to - theta_from = bearing - back_bearing + pi is known.
  double back_bearing = 0.0;
};

/// The camera that measures links. Appendix A's looming: the cylinder's pixel width is
/// inversely proportional to the distance, so a pixel's error grows the distance error with
/// its square; the thesis's CMUCam measured accurately up to about 1.1 m.
struct CameraModel {
  double max_range_m = 1.1;                ///< links longer than this cannot be measured
  double min_range_m = 0.1;                ///< nor shorter (the robots would touch)
  double length_sigma_at_max_m = 0.02;     ///< sigma of the length at max_range_m; ~ d^2 below
  double bearing_sigma = 0.0174532925199;  ///< rad (1 deg): the stepper's encoder
};

/// Checks the model; throws gridloc::Error naming the field.
void validate(const CameraModel& camera);

/// Sigma of a link length of d metres: length_sigma_at_max_m * (d / max_range_m)^2.
double length_sigma(const CameraModel& camera, double length_m);

/// Checks a link against the team size and camera; throws gridloc::Error naming the link
/// ("link 0-2: ..."): robots out of range or equal, a length that is not finite, beyond the
/// camera's range or below its minimum, a bearing that is not finite.
void validate(const VirtualLink& link, int robots, const CameraModel& camera);

/// Whether the segment between two positions crosses no wall of the map.
bool line_of_sight(const MapFeatures& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The link robot `from` at pose a measures to robot `to` at pose b, noise-free when seed is
/// 0, else with the camera's Gaussian errors drawn from Rng(seed).
VirtualLink measure_link(int from, int to, const Pose2& a, const Pose2& b,
                         const CameraModel& camera, std::uint64_t seed);

/// The links a team at these true poses can measure: every pair within the camera's range
/// with a line of sight (from the lower index to the higher), noise seeded per link from
/// seed (0: noise-free); a noisy length beyond the camera's limits is left out, as the camera
/// would fail to measure it.
std::vector<VirtualLink> measurable_links(const std::vector<Pose2>& poses, const MapFeatures& map,
                                          const CameraModel& camera, std::uint64_t seed);

/// Where `to` stands when `from` is at pose a: a's position + length along a.theta + bearing.
Eigen::Vector2d linked_position(const VirtualLink& link, const Pose2& a);

/// to's heading implied by from's heading (NaN without back_bearing).
double linked_heading(const VirtualLink& link, double from_heading);

}  // namespace gridloc
