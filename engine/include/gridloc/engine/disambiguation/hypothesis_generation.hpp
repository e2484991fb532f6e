#pragma once
/// Hypothesis generation (seed 002 §III): every start pose in a polygon map whose
/// range-limited view matches the visibility data W sensed at the unknown start. A view
/// that holds a vertex pins the candidates: that vertex must be one of the map's, so each
/// map vertex (and, up to rotation, each alignment of its walls with the seen wall) gives
/// one candidate pose, kept when its own view is the same as W.
#include <vector>

#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

struct HypothesisOptions {
  double range = kUnlimitedRange;  ///< the sensor's range d (> 0)
  /// false: the heading is known (seed 002's compass); true: match up to rotation too.
  bool rotation = false;
  double tolerance = 1e-6;  ///< of same_view, and to merge equal poses
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const HypothesisOptions& options);

/// The start poses (world) whose view (range_view at the pose, heading the pose's) is the
/// same as `sensed`, sorted by x, then y, then heading. With the heading known every pose
/// has heading `heading`. Throws gridloc::Error when `sensed` holds no vertex: its matches
/// then form a continuum, not a finite set (seed 002 assumes non-null W).
std::vector<Pose2> matching_starts(const Area& free_world, const RangeView& sensed, double heading,
                                   const HypothesisOptions& options = {});

/// matching_starts() for the view sensed at `true_start` (the simulated robot).
std::vector<Pose2> start_hypotheses(const Area& free_world, const Pose2& true_start,
                                    const HypothesisOptions& options = {});

/// The index in `hypotheses` of the pose within `tolerance` (m and rad) of `pose`, or -1.
int find_pose(const std::vector<Pose2>& hypotheses, const Pose2& pose, double tolerance = 1e-6);

}  // namespace gridloc
