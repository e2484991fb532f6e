#pragma once
// The image of `gridloc disambiguate` (seed 002's Figs 3, 4, 7 and 17): on the left the
// overlay in the robot's start frame — every hypothesis's map outlined, OI filled, the useful
// region U, the first round's random points, the path and its stops; on the right the map in
// the world with the hypotheses and the path drawn under each hypothesis still standing.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/grids/polygon_map.hpp"

namespace gridloc::cli {

struct DisambiguationPicture {
  std::string title;                           ///< first line (the map's name, the algorithm)
  std::string caption;                         ///< second line (path length, stops, bound)
  PolygonMap map;                              ///< world frame
  std::vector<Pose2> hypotheses;               ///< the robot's start under each (world)
  int true_hypothesis = -1;                    ///< index of the truth, -1 unknown
  std::vector<int> remaining;                  ///< hypotheses standing at the end
  Overlay overlay;                             ///< of the first stop (start frame)
  Region useful;                               ///< U of that overlay (empty for COL)
  std::vector<Eigen::Vector2d> samples;        ///< the first round's random points (start frame)
  std::vector<Eigen::Vector2d> path;           ///< start, bends, stops (start frame)
  std::vector<Eigen::Vector2d> stops;          ///< where the robot sensed (start frame)
  std::optional<Eigen::Vector2d> bound_point;  ///< the lower bound's nearest informative point
};

/// The two panels side by side with axes in map units, a legend below. Throws gridloc::Error
/// when an index of `remaining` or `true_hypothesis` (other than -1) names no hypothesis.
cv::Mat render_disambiguation(const DisambiguationPicture& picture);

}  // namespace gridloc::cli
