#pragma once
// Plotting primitives for gridloc's images (OpenCV): text, ticks, a plot area in metres,
// colour bar, scale bar, polygon rings, pose markers and legends. Dark text on white margins.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridloc/grids/grid.hpp"

namespace gridloc::cli::plot {

// Colours are BGR.
inline const cv::Scalar kInk(30, 30, 30);            ///< text and axes
inline const cv::Scalar kWhite(255, 255, 255);       ///< halos, backgrounds
inline const cv::Scalar kEstimate(30, 30, 220);      ///< the refined estimate: red
inline const cv::Scalar kTruth(210, 40, 210);        ///< the truth: magenta
inline const cv::Scalar kWindow(255, 255, 255);      ///< the search window outline
inline const cv::Scalar kGridLine(228, 228, 228);    ///< light grid lines of line plots
inline const cv::Scalar kSwatchEdge(150, 150, 150);  ///< legend boxes' outline

constexpr double kTickScale = 0.45;   ///< tick labels, legends
constexpr double kLabelScale = 0.5;   ///< axis labels
constexpr double kTitleScale = 0.62;  ///< the title line

/// Writes `img` as a PNG; gridloc::Error naming `path` when it cannot.
void write_png(const std::string& path, const cv::Mat& img);

/// Draws `s` with its baseline's left end at `org` (anti-aliased Hershey simplex).
void text(cv::Mat& img, const std::string& s, cv::Point org, double scale,
          const cv::Scalar& colour = kInk, int thickness = 1);
/// The same with a white halo, readable over any colour.
void halo_text(cv::Mat& img, const std::string& s, cv::Point org, double scale,
               const cv::Scalar& colour = kInk, int thickness = 1);
cv::Size text_size(const std::string& s, double scale, int thickness = 1);

/// Greedy word wrap of `s` into lines at most `width` px wide at `scale` (a word longer than
/// the width gets a line of its own).
std::vector<std::string> wrap(const std::string& s, double scale, int thickness, int width);

/// The title lines (kTitleScale, bold, 28 px apart), then the caption lines (kTickScale, 20 px
/// apart), from the top left of the image.
void title_block(cv::Mat& img, const std::vector<std::string>& title,
                 const std::vector<std::string>& caption);
/// The row just below title_block()'s lines.
int title_block_bottom(std::size_t title_lines, std::size_t caption_lines);

/// `v` with `digits` decimals.
std::string fixed(double v, int digits);
/// `v` with about four significant digits, without trailing zeros.
std::string number(double v);
/// The smallest of 1, 2, 5 x 10^k that is >= `at_least` (> 0).
double nice_step(double at_least);

/// A plot area showing the grid-frame rectangle [x0, x1] x [y0, y1] (m) at `scale` px/m,
/// its top-left corner at canvas pixel `origin`; y grows upwards.
struct View {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;
  double scale = 100.0;
  cv::Point origin;

  int width() const;
  int height() const;
  cv::Rect rect() const { return {origin.x, origin.y, width(), height()}; }
  /// Canvas pixel (fractional) of grid-frame point (x, y).
  cv::Point2d px(double x, double y) const {
    return {origin.x + (x - x0) * scale, origin.y + (y1 - y) * scale};
  }
  /// Grid-frame point at the centre of plot pixel (column c, row r) of the plot area.
  cv::Point2d at(int c, int r) const { return {x0 + (c + 0.5) / scale, y1 - (r + 0.5) / scale}; }
};

/// An axis-aligned box (m) of the finite points added to it.
struct Box {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;

  void add(const Eigen::Vector2d& p) {
    if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  void add(const std::vector<Eigen::Vector2d>& points) {
    for (const Eigen::Vector2d& p : points) add(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

/// The box grown by `margin_fraction` of its longer side on each side; a box under 1 cm (or
/// empty: the origin) becomes a 1 m square about its centre.
Box padded(Box box, double margin_fraction);

/// px/m showing a w x h m region about `target_px` wide, with cells of `cell` m at least
/// 4 px unless that makes the plot larger than 1600 px.
double fit_scale(double w, double h, double cell, double target_px);

/// Sub-pixel point for OpenCV's drawing functions with shift = kShift.
constexpr int kShift = 4;
cv::Point sub(const cv::Point2d& p);
void line(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
          int thickness);
void dashed_line(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& colour,
                 int thickness, double dash = 6.0);
void circle(cv::Mat& img, const cv::Point2d& c, double radius, const cv::Scalar& colour,
            int thickness);

/// Closed rings as sub-pixel points (kShift); an empty ring is skipped.
using Contours = std::vector<std::vector<cv::Point>>;
/// Fills the rings together (even-odd: holes stay unfilled).
void fill_rings(cv::Mat& img, const Contours& rings, const cv::Scalar& colour);
void outline_rings(cv::Mat& img, const Contours& rings, const cv::Scalar& colour, int thickness);

/// The image direction (unit, rows growing downwards) of grid-frame heading `heading` (rad,
/// counter-clockwise from +x).
cv::Point2d direction(double heading);

/// Frame of the plot area and metre ticks below and left of it; tick labels add (ox, oy) to
/// grid-frame coordinates (the map origin: world coordinates when the yaw is 0).
void axes_m(cv::Mat& img, const View& v, double ox, double oy, const std::string& x_label,
            const std::string& y_label);

/// A vertical viridis bar left-aligned at `x`, spanning `top`..`bottom`, labelled from
/// `lo` (bottom) to `hi` (top), `title` above it. `lut` is the 256-entry colour map.
void colour_bar(cv::Mat& img, const cv::Mat& lut, int x, int top, int bottom, double lo, double hi,
                const std::string& title);

/// The occupancy map under the plot area (`img` is the area, `view` its view with origin
/// 0): each pixel its cell's state, occupied dark grey, unknown (and beyond the grid) light
/// grey, free white.
void paint_grid(cv::Mat& img, const OccupancyMap& map, const View& view);
/// A scale bar of a round length in the lower-left corner of the plot area, on a white box.
void scale_bar(cv::Mat& img, const View& v);

/// The refined estimate: a red disc with a white rim and a heading line (`heading` is the
/// grid-frame angle, counter-clockwise from +x).
void estimate_marker(cv::Mat& img, const cv::Point2d& p, double heading);
/// Hypothesis `n`: a small white disc with a heading tick (none when `heading` is NaN), its
/// number beside it.
void hypothesis_marker(cv::Mat& img, const cv::Point2d& p, double heading, int n);
/// The truth: a magenta cross with a heading line.
void truth_marker(cv::Mat& img, const cv::Point2d& p, double heading);

/// A legend: each item draws its symbol about a point (it may reach 36 px to the right), then
/// its label follows.
struct LegendItem {
  std::function<void(cv::Mat&, const cv::Point2d&)> symbol;
  std::string label;
};
/// Lays the items out left to right from (x, y) (y = the text baseline), wrapping before
/// `max_x`; returns the baseline of the last row.
int legend(cv::Mat& img, const std::vector<LegendItem>& items, int x, int y, int max_x);
/// A legend swatch: a 24 x 14 px box filled by `fill`, outlined in kSwatchEdge.
LegendItem swatch(std::function<void(cv::Mat&, const cv::Rect&)> fill, std::string label);
/// A legend swatch of one colour.
LegendItem filled(const cv::Scalar& colour, std::string label);
/// A legend line 26 px long.
LegendItem stroke(const cv::Scalar& colour, int thickness, std::string label);

/// The viridis colour map as a 256 x 1 BGR table (cv::applyColorMap, COLORMAP_VIRIDIS).
cv::Mat viridis();

}  // namespace gridloc::cli::plot
