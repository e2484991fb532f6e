// The x, y image of `gridloc heatmap` (issue 4): the score over the map at the best heading
// or its maximum over the headings, in viridis over the grey map, the window and the marks.
#include "heatmap_render.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "heatmap_layout.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using layout::blend;
using layout::canvas;
using layout::draw_covariance;
using layout::draw_estimate_and_truth;
using layout::draw_hypotheses;
using layout::draw_scale_and_axes;
using layout::grey;
using layout::infinity;
using layout::kAxisBelow;
using layout::kFreeGrey;
using layout::kOccupiedGrey;
using layout::kUnknownGrey;
using layout::legend_and_crop;
using layout::pose_legend;
using layout::title;
using plot::View;

constexpr double kHeatAlpha = 0.78;

/// The scores of one x, y image (ny rows of nx) and their range.
struct ScoreSlice {
  std::vector<double> scores;
  double lo = 0.0, hi = 0.0;
};

/// The scores at the best heading, or their maximum over the headings of each cell.
ScoreSlice score_slice(const ScoreVolume& volume, bool max_over_headings) {
  ScoreSlice slice;
  slice.scores.assign(static_cast<std::size_t>(volume.nx) * volume.ny, -infinity());
  for (int t = 0; t < volume.headings; ++t) {
    if (!max_over_headings && t != volume.best.it) continue;
    for (int y = 0; y < volume.ny; ++y) {
      for (int x = 0; x < volume.nx; ++x) {
        double& s = slice.scores[static_cast<std::size_t>(y) * volume.nx + x];
        s = std::max(s, volume.at(x, y, t));
      }
    }
  }
  const auto [lo_it, hi_it] = std::minmax_element(slice.scores.begin(), slice.scores.end());
  slice.lo = *lo_it;
  slice.hi = *hi_it;
  return slice;
}

/// The search window's cells in the grid frame (m).
struct WindowBox {
  double x0, x1, y0, y1;
};

WindowBox window_box(const ScoreVolume& volume) {
  const double res = volume.resolution;
  return {volume.ix0 * res, (volume.ix0 + volume.nx) * res, volume.iy0 * res,
          (volume.iy0 + volume.ny) * res};
}

/// The window's cells and a margin around them (about 60 % of the window, 0.5 to 1.5 m),
/// the truth too, within the map.
View score_view(const ScoreVolume& volume, const WindowBox& w, const HeatmapMarks& marks) {
  const GridGeometry& grid = volume.geometry;
  const double res = volume.resolution;
  View view;
  const double margin = std::clamp(0.6 * std::max(w.x1 - w.x0, w.y1 - w.y0), 0.5, 1.5);
  view.x0 = w.x0 - margin;
  view.x1 = w.x1 + margin;
  view.y0 = w.y0 - margin;
  view.y1 = w.y1 + margin;
  if (marks.truth) {
    const Pose2 t = grid.to_grid_frame(*marks.truth);
    view.x0 = std::min(view.x0, t.x - 0.5);
    view.x1 = std::max(view.x1, t.x + 0.5);
    view.y0 = std::min(view.y0, t.y - 0.5);
    view.y1 = std::max(view.y1, t.y + 0.5);
  }
  view.x0 = std::max(view.x0, 0.0);
  view.y0 = std::max(view.y0, 0.0);
  view.x1 = std::min(view.x1, grid.width * res);
  view.y1 = std::min(view.y1, grid.height * res);
  view.scale = plot::fit_scale(view.x1 - view.x0, view.y1 - view.y0, res, 640.0);
  return view;
}

/// The grey level of the map cell under grid-frame point `p` (unknown outside the map).
double map_grey(const OccupancyMap& map, const cv::Point2d& p) {
  const Cell mc = map.geometry.cell_of(p.x, p.y);
  double gl = kUnknownGrey;
  if (map.geometry.contains(mc.ix, mc.iy)) {
    const CellState s = map.at(mc.ix, mc.iy);
    gl = s == CellState::Free ? kFreeGrey
                              : (s == CellState::Occupied ? kOccupiedGrey : kUnknownGrey);
  }
  return gl;
}

/// Map in grey, the score in viridis over it (semi-transparent: walls show through).
void paint_scores_on_map(cv::Mat& img, const View& view, const OccupancyMap& map,
                         const ScoreVolume& volume, const ScoreSlice& slice, const cv::Mat& lut) {
  const double res = volume.resolution;
  const double lo = slice.lo, hi = slice.hi;
  for (int r = 0; r < view.height(); ++r) {
    auto* row = img.ptr<cv::Vec3b>(view.origin.y + r) + view.origin.x;
    for (int c = 0; c < view.width(); ++c) {
      const cv::Point2d p = view.at(c, r);
      row[c] = grey(map_grey(map, p));
      const int x = static_cast<int>(std::floor(p.x / res)) - volume.ix0;
      const int y = static_cast<int>(std::floor(p.y / res)) - volume.iy0;
      if (x < 0 || y < 0 || x >= volume.nx || y >= volume.ny) continue;
      const double s = slice.scores[static_cast<std::size_t>(y) * volume.nx + x];
      const int k = hi > lo ? static_cast<int>(std::lround(255.0 * (s - lo) / (hi - lo))) : 255;
      row[c] = blend(lut.at<cv::Vec3b>(k), row[c], kHeatAlpha);
    }
  }
}

/// The search window (clipped to the map), dark then white so that it shows on any colour.
void draw_window(cv::Mat& img, const View& view, const WindowBox& w) {
  const cv::Point2d a = view.px(w.x0, w.y1), b = view.px(w.x1, w.y0);
  cv::rectangle(img, plot::sub(a), plot::sub(b), plot::kInk, 3, cv::LINE_AA, plot::kShift);
  cv::rectangle(img, plot::sub(a), plot::sub(b), plot::kWindow, 1, cv::LINE_AA, plot::kShift);
}

/// The title of an x, y image.
std::string score_xy_title(const ScoreVolume& volume, bool max_over_headings) {
  const double best_deg =
      rad2deg(volume.theta0 + volume.geometry.yaw + volume.best.it * volume.step_theta);
  return max_over_headings
             ? "Score S over x, y: maximum over the " + std::to_string(volume.headings) +
                   " headings"
             : "Score S over x, y at the best heading, " + plot::fixed(best_deg, 1) + " deg";
}

/// The poses, the hypotheses and the search window.
std::vector<plot::LegendItem> score_xy_legend(const HeatmapMarks& marks) {
  auto items = pose_legend(marks);
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     plot::hypothesis_marker(m, p + cv::Point2d(12, 0), 0.0, 1);
                   },
                   "hypotheses, best first"});
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     cv::ellipse(m, cv::RotatedRect(cv::Point2f(p), cv::Size2f(22, 10), 0.0f),
                                 plot::kEstimate, 1, cv::LINE_AA);
                   },
                   "covariance, 95 % ellipse"});
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     const cv::Point2d d(10.0, 6.0);
                     cv::rectangle(m, plot::sub(p - d), plot::sub(p + d), cv::Scalar(90, 90, 90),
                                   cv::FILLED, cv::LINE_AA, plot::kShift);
                     cv::rectangle(m, plot::sub(p - d), plot::sub(p + d), plot::kWindow, 1,
                                   cv::LINE_AA, plot::kShift);
                   },
                   "search window"});
  for (plot::LegendItem& item : layout::map_legend()) items.push_back(std::move(item));
  return items;
}

}  // namespace

cv::Mat render_score_xy(const ScoreVolume& volume, const OccupancyMap& map,
                        const HeatmapMarks& marks, bool max_over_headings) {
  const ScoreSlice slice = score_slice(volume, max_over_headings);
  const WindowBox window = window_box(volume);
  View view = score_view(volume, window, marks);
  cv::Mat img = canvas(view, 130, kAxisBelow + 100, marks.caption);
  const cv::Mat lut = plot::viridis();
  paint_scores_on_map(img, view, map, volume, slice, lut);
  draw_window(img, view, window);
  draw_hypotheses(img, view, volume.geometry, marks);
  draw_covariance(img, view, volume.geometry, marks);
  draw_estimate_and_truth(img, view, volume.geometry, marks);
  draw_scale_and_axes(img, view, volume.geometry);
  const cv::Rect pr = view.rect();
  plot::colour_bar(img, lut, pr.x + pr.width + 22, pr.y, pr.y + pr.height, slice.lo, slice.hi,
                   "score S");
  title(img, score_xy_title(volume, max_over_headings), marks.caption);
  return legend_and_crop(img, score_xy_legend(marks), pr);
}

}  // namespace gridloc::cli
