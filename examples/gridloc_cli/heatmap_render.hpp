#pragma once
// The images of `gridloc heatmap` (issue 4), drawn with OpenCV: the score surface over the
// map, the score against heading, the local grid on the global grid. OpenCV stays in the
// command-line tool; the engine only hands over a ScoreVolume. Images are drawn in the grid
// frame (x along columns, y along rows): the world frame when the map's yaw is 0.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::cli {

/// What the images mark, world frame.
struct HeatmapMarks {
  Pose2 estimate;                      ///< the refined pose
  std::vector<Hypothesis> hypotheses;  ///< distinct peaks, best first (1 = the lattice winner)
  std::optional<Pose2> truth;          ///< when known
  std::string caption;                 ///< under the title, '\n' between lines: map, window
  std::string verdict;                 ///< the estimate's verdict, named in the legend...
  double confidence = 0.0;             ///< ...with its confidence
  /// The estimate's covariance (world frame, x y theta); its x, y part is drawn as the 95 %
  /// ellipse on the x, y images (nothing when zero).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// The score over x, y at the best heading (`max_over_headings` false) or its maximum over
/// the headings of each cell, in viridis over a grey rendering of `map` around the window,
/// with a colour bar, axes in metres, a scale bar, the window outline and the marks.
cv::Mat render_score_xy(const ScoreVolume& volume, const OccupancyMap& map,
                        const HeatmapMarks& marks, bool max_over_headings);

/// The maximum over x, y of the score against heading (world frame, degrees), the
/// estimate's, the hypotheses' and the truth's headings marked.
cv::Mat render_score_theta(const ScoreVolume& volume, const HeatmapMarks& marks);

/// The padded global grid `global` (free light, occupied dark, unknown mid-grey) with `local`
/// overlaid, its robot cell on map cell `robot`; `geometry` is the unpadded finest grid's
/// (ScoreVolume::geometry). The robot is drawn at marks.estimate with `footprint` (a disc when
/// empty), the truth when known.
cv::Mat render_local_overlay(const PaddedGrid& global, const GridGeometry& geometry,
                             const SparseLocalGrid& local, const Cell& robot,
                             const Footprint& footprint, const HeatmapMarks& marks);

}  // namespace gridloc::cli
