#include "heatmap_layout.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace gridloc::cli::layout {
namespace {

/// The canvas cut just below the legend's last row.
cv::Mat crop_below(const cv::Mat& img, int last_baseline) {
  return img.rowRange(0, std::min(img.rows, last_baseline + 16)).clone();
}

/// A pose as "(x, y m, theta deg)" for the legend.
std::string pose_text(const Pose2& p) {
  std::ostringstream s;  // not "(" + std::string: GCC 12 warns falsely (-Wrestrict) on that
  s << "(" << plot::fixed(p.x, 2) << ", " << plot::fixed(p.y, 2) << " m, "
    << plot::fixed(rad2deg(p.theta), 1) << " deg)";
  return s.str();
}

/// The name of a metre axis: "grid x (m)" when the grid is rotated.
std::string axis_name(const GridGeometry& grid, const char* axis) {
  return std::string(grid.yaw == 0.0 ? "" : "grid ") + axis + " (m)";
}

/// Tick label offsets: world coordinates when the grid is not rotated.
cv::Point2d tick_offset(const GridGeometry& grid) {
  return grid.yaw == 0.0 ? cv::Point2d(grid.origin.x(), grid.origin.y()) : cv::Point2d(0.0, 0.0);
}

}  // namespace

double infinity() {
  return std::numeric_limits<double>::infinity();
}

cv::Vec3b grey(double level) {
  const auto byte = static_cast<std::uint8_t>(std::lround(level));
  return {byte, byte, byte};
}

cv::Vec3b blend(const cv::Vec3b& top, const cv::Vec3b& under, double alpha) {
  cv::Vec3b out;
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::uint8_t>(std::lround(alpha * top[k] + (1.0 - alpha) * under[k]));
  }
  return out;
}

cv::Mat canvas(plot::View& view, int right, int below, const std::string& caption) {
  view.origin = {kLeft, kTop};
  int width = kLeft + view.width() + right;
  std::istringstream lines(caption);
  for (std::string line; std::getline(lines, line);) {
    width = std::max(width, plot::text_size(line, plot::kTickScale).width + 24);
  }
  return cv::Mat(kTop + view.height() + below, width, CV_8UC3, cv::Scalar(255, 255, 255));
}

void title(cv::Mat& img, const std::string& line1, const std::string& caption) {
  plot::text(img, line1, {12, 24}, plot::kTitleScale, plot::kInk, 2);
  std::istringstream lines(caption);
  std::string line;
  for (int y = 48; std::getline(lines, line); y += 20)
    plot::text(img, line, {12, y}, plot::kTickScale);
}

std::vector<plot::LegendItem> pose_legend(const HeatmapMarks& marks) {
  std::vector<plot::LegendItem> items;
  std::string estimate = "estimate " + pose_text(marks.estimate);
  if (!marks.verdict.empty()) {
    estimate += ": " + marks.verdict + ", confidence " + plot::fixed(marks.confidence, 2);
  }
  items.push_back(
      {[](cv::Mat& m, const cv::Point2d& p) { plot::estimate_marker(m, p, 0.0); }, estimate});
  if (marks.truth) {
    items.push_back({[](cv::Mat& m, const cv::Point2d& p) { plot::truth_marker(m, p, 0.0); },
                     "truth " + pose_text(*marks.truth)});
  }
  return items;
}

std::vector<plot::LegendItem> map_legend() {
  const auto swatch = [](double level) {
    return [level](cv::Mat& m, const cv::Point2d& p) {
      const cv::Rect r(static_cast<int>(p.x) + 2, static_cast<int>(p.y) - 7, 24, 14);
      cv::rectangle(m, r, cv::Scalar(level, level, level), cv::FILLED);
      cv::rectangle(m, r, plot::kSwatchEdge, 1);
    };
  };
  return {{swatch(kFreeGrey), "map free"},
          {swatch(kOccupiedGrey), "map occupied"},
          {swatch(kUnknownGrey), "map unknown, or outside it"}};
}

cv::Mat legend_and_crop(cv::Mat& img, const std::vector<plot::LegendItem>& items,
                        const cv::Rect& area) {
  const int last =
      plot::legend(img, items, 12, area.y + area.height + kAxisBelow + 20, img.cols - 8);
  return crop_below(img, last);
}

void draw_hypotheses(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                     const HeatmapMarks& marks) {
  // Lowest ranked first, so that the best lie on top.
  for (std::size_t k = marks.hypotheses.size(); k-- > 0;) {
    const Pose2 p = grid.to_grid_frame(marks.hypotheses[k].pose);
    plot::hypothesis_marker(img, view.px(p.x, p.y), p.theta, static_cast<int>(k) + 1);
  }
}

void draw_covariance(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                     const HeatmapMarks& marks) {
  // The x, y block in the grid frame: rotated by the map's yaw.
  const double c = std::cos(grid.yaw), s = std::sin(grid.yaw);
  Eigen::Matrix2d turn;
  turn << c, s, -s, c;
  const Eigen::Matrix2d xy = turn * marks.covariance.topLeftCorner<2, 2>() * turn.transpose();
  if (!(xy.trace() > 0.0) || !xy.allFinite()) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(xy);
  constexpr double kChi2_95 = 5.991;  // 95 % of a 2-D Gaussian lies within this squared radius
  const Eigen::Vector2d radii =
      (kChi2_95 * axes.eigenvalues().cwiseMax(0.0)).cwiseSqrt() * view.scale;
  const Eigen::Vector2d major = axes.eigenvectors().col(1);
  // Pixel rows grow downwards: the angle on the canvas is the grid angle negated.
  const double angle_deg = -std::atan2(major.y(), major.x()) * 180.0 / std::numbers::pi;
  const Pose2 e = grid.to_grid_frame(marks.estimate);
  const cv::Size2f size(static_cast<float>(2.0 * std::max(radii(1), 1.0)),
                        static_cast<float>(2.0 * std::max(radii(0), 1.0)));
  const cv::Point2d centre = view.px(e.x, e.y);
  cv::ellipse(img, cv::RotatedRect(cv::Point2f(centre), size, static_cast<float>(angle_deg)),
              plot::kWhite, 3, cv::LINE_AA);
  cv::ellipse(img, cv::RotatedRect(cv::Point2f(centre), size, static_cast<float>(angle_deg)),
              plot::kEstimate, 1, cv::LINE_AA);
}

void draw_estimate_and_truth(cv::Mat& img, const plot::View& view, const GridGeometry& grid,
                             const HeatmapMarks& marks) {
  if (marks.truth) {
    const Pose2 t = grid.to_grid_frame(*marks.truth);
    plot::truth_marker(img, view.px(t.x, t.y), t.theta);
  }
  const Pose2 e = grid.to_grid_frame(marks.estimate);
  plot::estimate_marker(img, view.px(e.x, e.y), e.theta);
}

void draw_scale_and_axes(cv::Mat& img, const plot::View& view, const GridGeometry& grid) {
  plot::scale_bar(img, view);
  const cv::Point2d o = tick_offset(grid);
  plot::axes_m(img, view, o.x, o.y, axis_name(grid, "x"), axis_name(grid, "y"));
}

}  // namespace gridloc::cli::layout
