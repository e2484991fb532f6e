// The heading image of `gridloc heatmap` (issue 4): the best score over x, y against the
// world heading, the estimate's, the truth's and the hypotheses' headings marked.
#include "heatmap_render.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "heatmap_layout.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using layout::canvas;
using layout::infinity;
using layout::kAxisBelow;
using layout::kLeft;
using layout::kTop;
using layout::legend_and_crop;
using layout::title;
using plot::View;

/// The heading of a world angle on an axis of world headings centred on `centre` (rad).
double unwrap(double theta, double centre) {
  return centre + normalize_angle(theta - centre);
}

const cv::Scalar kCurve(170, 90, 20);  // the curve of the best score per heading

/// World heading (rad) of volume heading index `t` (fractions allowed).
double world_heading(const ScoreVolume& volume, double t) {
  return volume.theta0 + volume.geometry.yaw + t * volume.step_theta;
}

/// The best score over x, y at each heading.
std::vector<double> heading_curve(const ScoreVolume& volume) {
  std::vector<double> curve(static_cast<std::size_t>(volume.headings), -infinity());
  for (int t = 0; t < volume.headings; ++t) {
    for (int y = 0; y < volume.ny; ++y) {
      for (int x = 0; x < volume.nx; ++x) curve[t] = std::max(curve[t], volume.at(x, y, t));
    }
  }
  return curve;
}

/// The axes of the heading plot: world heading (deg) across, score up, on plot area `area`.
struct HeadingAxes {
  double xlo = 0.0, xhi = 0.0;  // deg
  double ylo = 0.0, yhi = 0.0;  // score
  double centre = 0.0;          // world heading in the middle of the axis (rad)
  cv::Rect area;

  double fx(double deg) const { return area.x + (deg - xlo) / (xhi - xlo) * area.width; }
  double fy(double s) const { return area.y + (yhi - s) / (yhi - ylo) * area.height; }
};

/// The headings with a little padding, the curve's and the hypotheses' scores with 10 %.
HeadingAxes heading_axes(const ScoreVolume& volume, const std::vector<double>& curve,
                         const HeatmapMarks& marks, const cv::Rect& area) {
  HeadingAxes axes;
  axes.area = area;
  axes.centre = world_heading(volume, 0.5 * (volume.headings - 1));
  double xlo = rad2deg(world_heading(volume, 0)),
         xhi = rad2deg(world_heading(volume, volume.headings - 1));
  const double xpad = std::max(0.02 * (xhi - xlo), 0.5 * rad2deg(volume.step_theta));
  axes.xlo = xlo - xpad;
  axes.xhi = xhi + xpad;
  auto [lo_it, hi_it] = std::minmax_element(curve.begin(), curve.end());
  double ylo = *lo_it, yhi = *hi_it;
  for (const Hypothesis& h : marks.hypotheses) ylo = std::min(ylo, h.score);
  const double ypad = yhi > ylo ? 0.1 * (yhi - ylo) : 1.0;
  axes.ylo = ylo - ypad;
  axes.yhi = yhi + ypad;
  return axes;
}

/// Grid lines and ticks: headings at round degrees, scores at 1-2-5 steps; the frame and
/// the axis labels.
void draw_heading_grid(cv::Mat& img, const HeadingAxes& axes) {
  const cv::Rect& pr = axes.area;
  const double xlo = axes.xlo, xhi = axes.xhi, ylo = axes.ylo, yhi = axes.yhi;
  double xstep = 1.0;
  for (double s : {1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0}) {
    xstep = s;
    if (s * pr.width / (xhi - xlo) >= 60.0) break;
  }
  const double ystep = plot::nice_step((yhi - ylo) / 6.0);
  const int ydigits = ystep >= 1.0 ? 0 : (ystep >= 0.1 ? 1 : 2);
  for (double d = std::ceil(xlo / xstep) * xstep; d <= xhi; d += xstep) {
    const double x = axes.fx(d);
    plot::line(img, {x, static_cast<double>(pr.y)}, {x, static_cast<double>(pr.y + pr.height)},
               plot::kGridLine, 1);
    const std::string s = plot::fixed(d, 0);
    const cv::Size ts = plot::text_size(s, plot::kTickScale);
    plot::text(img, s,
               {static_cast<int>(std::lround(x)) - ts.width / 2, pr.y + pr.height + 8 + ts.height},
               plot::kTickScale);
  }
  for (double s = std::ceil(ylo / ystep) * ystep; s <= yhi; s += ystep) {
    const double y = axes.fy(s);
    plot::line(img, {static_cast<double>(pr.x), y}, {static_cast<double>(pr.x + pr.width), y},
               plot::kGridLine, 1);
    const std::string t = plot::fixed(s, ydigits);
    const cv::Size ts = plot::text_size(t, plot::kTickScale);
    plot::text(img, t, {pr.x - 8 - ts.width, static_cast<int>(std::lround(y)) + ts.height / 2},
               plot::kTickScale);
  }
  cv::rectangle(img, pr, plot::kInk, 1);
  const std::string xl = "heading (deg, world frame)";
  plot::text(img, xl,
             {pr.x + pr.width / 2 - plot::text_size(xl, plot::kLabelScale).width / 2,
              pr.y + pr.height + 42},
             plot::kLabelScale);
  plot::text(img, "best S over x, y", {8, pr.y - 10}, plot::kLabelScale);
}

/// A heading (world, rad) as a vertical line, labelled inside the plot in legend row `row`;
/// nothing when it is off the axis.
void draw_heading_line(cv::Mat& img, const HeadingAxes& axes, double theta,
                       const cv::Scalar& colour, bool dashed, const std::string& label, int row) {
  const cv::Rect& pr = axes.area;
  const double x = axes.fx(rad2deg(unwrap(theta, axes.centre)));
  if (x < pr.x || x > pr.x + pr.width) return;
  const cv::Point2d top(x, pr.y), bottom(x, pr.y + pr.height);
  if (dashed) {
    plot::dashed_line(img, top, bottom, colour, 2);
  } else {
    plot::line(img, top, bottom, colour, 2);
  }
  const cv::Size ts = plot::text_size(label, plot::kTickScale);
  const int tx = x + 6 + ts.width < pr.x + pr.width ? static_cast<int>(x) + 6
                                                    : static_cast<int>(x) - 6 - ts.width;
  plot::halo_text(img, label, {tx, pr.y + 18 + 20 * row}, plot::kTickScale, colour);
}

/// The curve, a dot per heading when they are far enough apart.
void draw_heading_curve(cv::Mat& img, const HeadingAxes& axes, const ScoreVolume& volume,
                        const std::vector<double>& curve) {
  std::vector<cv::Point> pts;
  for (int t = 0; t < volume.headings; ++t)
    pts.push_back(plot::sub({axes.fx(rad2deg(world_heading(volume, t))), axes.fy(curve[t])}));
  cv::polylines(img, pts, false, kCurve, 2, cv::LINE_AA, plot::kShift);
  if (axes.area.width / std::max(1, volume.headings) >= 6) {
    for (const cv::Point& p : pts)
      cv::circle(img, p, 3 << plot::kShift, kCurve, cv::FILLED, cv::LINE_AA, plot::kShift);
  }
}

/// The hypotheses at their heading and score, lowest ranked first.
void draw_hypothesis_scores(cv::Mat& img, const HeadingAxes& axes, const HeatmapMarks& marks) {
  const cv::Rect& pr = axes.area;
  for (std::size_t k = marks.hypotheses.size(); k-- > 0;) {
    const Hypothesis& h = marks.hypotheses[k];
    const double x = axes.fx(rad2deg(unwrap(h.pose.theta, axes.centre)));
    if (x < pr.x || x > pr.x + pr.width) continue;
    plot::hypothesis_marker(img, {x, axes.fy(h.score)}, std::nan(""), static_cast<int>(k) + 1);
  }
}

/// The curve, the estimate's heading, the hypotheses and the truth's heading.
std::vector<plot::LegendItem> score_theta_legend(const HeatmapMarks& marks) {
  std::vector<plot::LegendItem> items = {
      {[](cv::Mat& m, const cv::Point2d& p) {
         plot::line(m, p - cv::Point2d(12, 0), p + cv::Point2d(12, 0), kCurve, 2);
       },
       "best S over x, y"},
      {[](cv::Mat& m, const cv::Point2d& p) {
         plot::line(m, p - cv::Point2d(0, 9), p + cv::Point2d(0, 9), plot::kEstimate, 2);
       },
       "estimate heading"},
      {[](cv::Mat& m, const cv::Point2d& p) {
         plot::hypothesis_marker(m, p + cv::Point2d(12, 0), std::nan(""), 1);
       },
       "hypotheses (heading, score)"}};
  if (marks.truth) {
    items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                       plot::dashed_line(m, p - cv::Point2d(0, 9), p + cv::Point2d(0, 9),
                                         plot::kTruth, 2, 4.0);
                     },
                     "truth heading"});
  }
  return items;
}

}  // namespace

cv::Mat render_score_theta(const ScoreVolume& volume, const HeatmapMarks& marks) {
  const std::vector<double> curve = heading_curve(volume);
  constexpr int kW = 760, kH = 330;
  View frame;  // only for the canvas: kW x kH px
  frame.x1 = kW;
  frame.y1 = kH;
  frame.scale = 1.0;
  cv::Mat img = canvas(frame, 30, kAxisBelow + 80, marks.caption);
  const HeadingAxes axes = heading_axes(volume, curve, marks, cv::Rect(kLeft, kTop, kW, kH));
  draw_heading_grid(img, axes);
  // Truth and estimate headings as vertical lines, labelled inside the plot.
  draw_heading_line(img, axes, marks.estimate.theta, plot::kEstimate, false,
                    "estimate " + plot::fixed(rad2deg(marks.estimate.theta), 1), 0);
  if (marks.truth) {
    draw_heading_line(img, axes, marks.truth->theta, plot::kTruth, true,
                      "truth " + plot::fixed(rad2deg(marks.truth->theta), 1), 1);
  }
  draw_heading_curve(img, axes, volume, curve);
  draw_hypothesis_scores(img, axes, marks);
  title(img, "Score against heading: the best S over x, y at each heading", marks.caption);
  return legend_and_crop(img, score_theta_legend(marks), axes.area);
}

}  // namespace gridloc::cli
