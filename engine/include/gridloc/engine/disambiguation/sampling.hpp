#pragma once
/// Random points spread uniformly over a region (seed 002 §IV-A: "a set R of random points is
/// chosen by randomly sampling the interior of OI according to a uniform distribution").
#include <Eigen/Core>
#include <vector>

#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

/// `count` points uniform over the region's area: an area drawn in proportion to its size,
/// then a point of its bounding box kept when the area covers it. Empty for an empty region
/// (total size 0). Deterministic for the generator's state.
std::vector<Eigen::Vector2d> sample_uniform(const Region& region, int count, Rng& rng);

/// The points of a square lattice of spacing `step` (offset by half a step from the region's
/// bounding box) that the region covers: a fine, deterministic sampling. Throws
/// gridloc::Error for a step that is not > 0 or a lattice over 5e7 points per area.
std::vector<Eigen::Vector2d> sample_lattice(const Region& region, double step);

}  // namespace gridloc
