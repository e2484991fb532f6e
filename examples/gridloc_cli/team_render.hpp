#pragma once
// The image of `gridloc team` (seed 003's Figs 13, 14, 18 and 22): the map, each robot's
// candidate locations in its colour (single poses as heading marks, wall placements as
// stretches), the links between the solution's robots, and the solutions: the best drawn
// solid, its rivals dashed; the true poses when known.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/team/team_localization.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc::cli {

struct TeamPicture {
  std::string title;                                   ///< first line (the map's name, the sensor)
  std::string caption;                                 ///< second line (the verdict, the solutions)
  std::optional<PolygonMap> polygons;                  ///< drawn as rings when given
  OccupancyMap grid;                                   ///< else drawn as the occupancy image
  MapFeatures features;                                ///< walls (and corners, marked small)
  std::vector<std::vector<PoseCandidate>> candidates;  ///< per robot
  std::vector<TeamSolution> solutions;                 ///< best first; may be empty
  std::vector<VirtualLink> links;                      ///< as measured
  std::vector<int> links_used;                         ///< indices into links
  std::vector<Pose2> truth;                            ///< per robot, or empty
};

/// One panel, the map in world metres with axes, a legend below naming every colour.
/// Throws gridloc::Error when the per-robot vectors disagree in size with each other or a
/// link names a robot that is not there.
cv::Mat render_team(const TeamPicture& picture);

}  // namespace gridloc::cli
