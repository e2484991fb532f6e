#pragma once
/// Drawing the trials of seed 001's evaluation protocol (§4, §6): true poses in free space
/// away from walls, furniture the map does not have, and priors perturbed within the search
/// window. Each function draws from the caller's Rng in a fixed order: that order is the
/// protocol (the same seed gives the same trials).
#include "gridloc/engine/estimate.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/free_pose.hpp"  // sample_free_pose, pose_is_free: the trials' poses
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// `map` with 2-4 boxes (0.3-0.8 m) added on free cells at least `keep_clear` m from
/// `keep`: furniture the known map does not have.
OccupancyMap add_furniture(const OccupancyMap& map, const Pose2& keep, double keep_clear, Rng& rng);

/// A trial's prior: the search window and whether the truth lies outside it.
struct PerturbedPrior {
  SearchWindow window;
  bool wrong_prior = false;
};

/// `window` (its centre ignored) centred on `truth` moved uniformly within its half sizes;
/// when `wrong_prior`, one axis moved 1.5-3 half sizes off instead, so that the truth lies
/// outside. The centre is then pulled back onto the map of `geometry`; a wrong prior that
/// holds the truth again after that is not one.
PerturbedPrior perturb_prior(SearchWindow window, const Pose2& truth, bool wrong_prior,
                             const GridGeometry& geometry, Rng& rng);

}  // namespace gridloc
