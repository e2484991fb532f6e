#pragma once
// The page every image of `gridloc heatmap` shares (issue 4): a white canvas with the plot
// area at (kLeft, kTop), the title and caption above it, the legend below it, the grey levels
// of the map and the pose marks. heatmap_score_xy.cpp, heatmap_score_theta.cpp and
// heatmap_overlay.cpp draw the images on it.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "heatmap_render.hpp"
#include "plot.hpp"

namespace gridloc::cli::layout {

constexpr int kLeft = 72;       // room for the y tick labels
constexpr int kTop = 104;       // title, two caption lines, the y axis label
constexpr int kAxisBelow = 56;  // x tick labels and axis label

// Grey levels of the map under the heat: free, occupied, unknown.
constexpr double kFreeGrey = 250.0, kOccupiedGrey = 60.0, kUnknownGrey = 200.0;

/// +infinity, the start of a running maximum (-infinity()).
double infinity();

/// The grey pixel of `level` (rounded).
cv::Vec3b grey(double level);

/// `top` over `under` with opacity `alpha`, each channel rounded.
cv::Vec3b blend(const cv::Vec3b& top, const cv::Vec3b& under, double alpha);

/// A white canvas with the plot area of `view` at (kLeft, kTop), `right` px beside it and
/// `below` px under it, wide enough for the caption's lines.
cv::Mat canvas(plot::View& view, int right, int below, const std::string& caption);

/// The title, then the caption's lines ('\n' separated).
void title(cv::Mat& img, const std::string& line1, const std::string& caption);

/// The legend entries every map-like image shares.
std::vector<plot::LegendItem> pose_legend(const HeatmapMarks& marks);

/// The legend `items` below the plot area `area` and its x axis, the canvas cut just below
/// the legend's last row.
cv::Mat legend_and_crop(cv::Mat& img, const std::vector<plot::LegendItem>& items,
                        const cv::Rect& area);

/// The hypotheses, numbered, lowest ranked first so that the best lie on top.
void draw_hypotheses(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                     const HeatmapMarks& marks);

/// The map's cell greys (free, occupied, unknown or outside the map) as legend items.
std::vector<plot::LegendItem> map_legend();

/// The estimate's 95 % covariance ellipse in x, y (nothing for a zero covariance).
void draw_covariance(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                     const HeatmapMarks& marks);

/// The truth (when known), then the estimate over it.
void draw_estimate_and_truth(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                             const HeatmapMarks& marks);

/// The scale bar and the metre axes of a map-like image: world coordinates when the grid is
/// not rotated, grid coordinates otherwise.
void draw_scale_and_axes(cv::Mat& img, const plot::View& view, const GridGeometry& grid);

}  // namespace gridloc::cli::layout
