#pragma once
/// Whether a scan placed on a map sees through its walls (issue 35: never confidently
/// wrong). A scan at its true pose ends its beams on the walls that stopped them; placed at a
/// look-alike place it fits some walls and shoots others' beams through walls of the map.
/// The correlation's fit counts the returns that land on walls, not the beams that cross
/// them, so a weak fit at a wrong place and one at the right place read alike: this tells
/// them apart (on 660 held-out scans of 11 real buildings the right answers had at most 21 %
/// of their returns through a wall, half the wrong ones 25-59 %).
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

struct ThroughWalls {
  int returns = 0;  ///< the scan's returns (ranges short of its max range)
  int through = 0;  ///< those whose beam crossed an occupied cell before its end
  /// through / returns; 0 for a scan with no return.
  double share() const { return returns > 0 ? static_cast<double>(through) / returns : 0.0; }
};

/// The returns of `scan`, taken at `pose` on `map` (the sensor at the pose, its beams at the
/// scan's angles from the pose's heading), whose beam crosses an Occupied cell more than
/// `margin_m` before its return (the pose's own error and the map's blur stay within the
/// margin). Cells off the map count as free. Throws gridloc::Error for a negative or
/// non-finite margin or a scan that fails validate().
ThroughWalls through_walls(const OccupancyMap& map, const RangeScan& scan, const Pose2& pose,
                           double margin_m);

}  // namespace gridloc
