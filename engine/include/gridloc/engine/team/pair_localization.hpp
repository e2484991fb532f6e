#pragma once
/// Pair localization (seed 003 ch. III B, eqs. 3.25-3.30): the pairs of candidates of two
/// linked robots whose placements agree with the link, with a line of sight between them.
/// Two wall placements along parallel walls can agree all along a stretch: such a pair
/// slides (both robots move together along the walls) and is reported with its stretch.
#include <Eigen/Core>
#include <vector>

#include "gridloc/engine/team/map_features.hpp"
#include "gridloc/engine/team/pose_candidates.hpp"
#include "gridloc/engine/team/virtual_link.hpp"

namespace gridloc {

/// A stretch along which a solution may move rigidly: every pose moved by t * direction for t
/// in [0, length].
struct Slide {
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  double length = 0.0;  ///< m; 0: no slide, the poses are fixed
  bool moving() const { return length > 0.0; }
};

/// One placement of the link's two robots.
struct PairSolution {
  int candidate_from = -1, candidate_to = -1;  ///< indices into the robots' candidates
  Pose2 from, to;
  Slide slide;              ///< length 0: fixed
  double residual_m = 0.0;  ///< how far the link misses (after sliding the segments)
  double weight = 0.0;      ///< the two candidates' weights summed
};

/// How much disagreement a link tolerates: the gate (m) is gate_sigmas x the combined sigma
/// of the two placements (placement_sigma_m each, plus the heading's lever arm) and the
/// camera's length and bearing errors at the link's length.
struct LinkGateOptions {
  double placement_sigma_m = 0.015;        ///< of a candidate's position
  double heading_sigma = 0.0261799387799;  ///< rad (1.5 deg), of a candidate's heading
  double gate_sigmas = 3.0;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const LinkGateOptions& options);

/// The position gate (m) of a link, and its heading gate (rad) for the relative heading.
double position_gate(const VirtualLink& link, const CameraModel& camera,
                     const LinkGateOptions& options);
double heading_gate(const CameraModel& camera, const LinkGateOptions& options);

/// Every pair (a in from_candidates, b in to_candidates) that the link joins within its gate:
/// b's position is a's plus the link's vector along a's heading plus the bearing, b's heading
/// agrees with the relative heading when the link has one, and the segment between them has
/// a line of sight on the map. Best residual first.
std::vector<PairSolution> localize_pair(const std::vector<PoseCandidate>& from_candidates,
                                        const std::vector<PoseCandidate>& to_candidates,
                                        const VirtualLink& link, const MapFeatures& map,
                                        const CameraModel& camera,
                                        const LinkGateOptions& options = {});

}  // namespace gridloc
