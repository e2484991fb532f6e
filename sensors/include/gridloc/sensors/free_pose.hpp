#pragma once
/// Free poses on a map for a robot's footprint: where a robot can stand, clear of the walls
/// (the evaluation protocols draw their true poses with it, a navigation stack its test
/// poses or goals). Kept out of the evaluation so that a robot application links the
/// estimators alone (issue 31).
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// Draws a pose uniformly in the map whose footprint, grown by `clearance`, covers only free
/// cells. Throws gridloc::Error when none is found in many attempts.
Pose2 sample_free_pose(const OccupancyMap& map, const SonarRing& ring, double clearance, Rng& rng);

/// Whether the footprint of `ring` at world pose `pose`, grown by `clearance`, covers only
/// free cells: the test sample_free_pose draws against.
bool pose_is_free(const OccupancyMap& map, const SonarRing& ring, const Pose2& pose,
                  double clearance);

}  // namespace gridloc
