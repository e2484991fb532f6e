#pragma once
/// A world of line segments (walls) and an exact, noise-free laser ray caster against it: scan
/// matchers can then be checked against a known motion to the last bit, with no grid rounding.
#include <Eigen/Core>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// A wall from a to b, world frame (m).
using WallSegment = Segment2;

/// A noise-free scan of `walls` from world pose `pose`: beam k at robot-frame angle
/// first_angle + k * angle_step (rad) reads the distance to the nearest wall it crosses (ends
/// included; walls parallel to the beam are not seen), or exactly max_range when there is none
/// closer than max_range. Throws gridloc::Error naming the field for beams < 1, a non-positive
/// or non-finite angle_step or max_range, a non-finite first_angle or pose.
RangeScan simulate_segment_scan(const std::vector<WallSegment>& walls, const Pose2& pose, int beams,
                                double first_angle, double angle_step, double max_range);

/// The hallway of the seed 004 §4 simulation (robust ICP tests and bench_icp.cpp): 10 m x 2 m
/// (x in [-4, 6], y in [-1, 1]) with a door recess in the top wall (x in [1, 2], up to
/// y = 1.6), an alcove (x in [3, 3.8], down to y = -1.5) and a pillar (x in [-1.5, -1.2], up to
/// y = -0.7) on the bottom wall, and a free-standing 0.3 m square column (x in [-2.5, -2.2],
/// y in [0.2, 0.5]). 20 segments.
std::vector<WallSegment> seed004_hallway();

}  // namespace gridloc
