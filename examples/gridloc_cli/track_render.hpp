#pragma once
// gridloc track --plot (issue 34): the map with the track coloured by verdict, the truth when
// the log's poses are corrected, the finished searches and the rejected jumps; below it the
// places' weights over the updates, with the searches under way shaded; a legend.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/log_tracking.hpp"

namespace gridloc::cli {

struct TrackPicture {
  OccupancyMap map;
  std::vector<TrackStep> steps;  ///< the processed scans, in order
  std::vector<Pose2> truth;      ///< one per step, or empty
  std::string title, caption;
};

/// The picture; gridloc::Error when `truth` is neither empty nor one per step.
cv::Mat render_track(const TrackPicture& picture);

}  // namespace gridloc::cli
