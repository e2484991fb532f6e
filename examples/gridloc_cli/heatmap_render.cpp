#include "heatmap_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "heatmap_layout.hpp"
#include "heatmap_plot.hpp"

namespace gridloc::cli {
namespace {

using layout::blend;
using layout::canvas;
using layout::draw_estimate_and_truth;
using layout::draw_hypotheses;
using layout::draw_scale_and_axes;
using layout::grey;
using layout::kAxisBelow;
using layout::kFreeGrey;
using layout::kLeft;
using layout::kOccupiedGrey;
using layout::kTop;
using layout::kUnknownGrey;
using layout::legend_and_crop;
using layout::pose_legend;
using layout::title;
using plot::View;
using Symbol = decltype(plot::LegendItem::symbol);

constexpr double kHeatAlpha = 0.78;

double infinity() {
  return std::numeric_limits<double>::infinity();
}

cv::Vec3b to_vec(const cv::Scalar& s) {
  return {static_cast<std::uint8_t>(s[0]), static_cast<std::uint8_t>(s[1]),
          static_cast<std::uint8_t>(s[2])};
}

/// The heading of a world angle on an axis of world headings centred on `centre` (rad).
double unwrap(double theta, double centre) {
  return centre + normalize_angle(theta - centre);
}

// ---- the score over x, y ----------------------------------------------------------------

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
                     const cv::Point2d d(10.0, 6.0);
                     cv::rectangle(m, plot::sub(p - d), plot::sub(p + d), cv::Scalar(90, 90, 90),
                                   cv::FILLED, cv::LINE_AA, plot::kShift);
                     cv::rectangle(m, plot::sub(p - d), plot::sub(p + d), plot::kWindow, 1,
                                   cv::LINE_AA, plot::kShift);
                   },
                   "search window"});
  return items;
}

// ---- the score against heading ----------------------------------------------------------

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

// ---- the local grid on the global grid --------------------------------------------------

const cv::Vec3b kArcOnWall = to_vec(cv::Scalar(0, 0, 200));    // red
const cv::Vec3b kArc = to_vec(cv::Scalar(0, 150, 255));        // orange
const cv::Vec3b kFreeCell = to_vec(cv::Scalar(235, 140, 40));  // blue

/// Bounds of the local grid's cells (inclusive, robot cell 0) and of its positive cells and
/// the robot.
struct LocalBounds {
  int lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;  // local bounds, inclusive
  int px0 = 0, py0 = 0, px1 = 0, py1 = 0;  // bounds of the positive cells and the robot
};

LocalBounds local_bounds(const SparseLocalGrid& local) {
  LocalBounds b;
  for (std::size_t k = 0; k < local.size(); ++k) {
    b.lx0 = std::min(b.lx0, local.dx[k]);
    b.lx1 = std::max(b.lx1, local.dx[k]);
    b.ly0 = std::min(b.ly0, local.dy[k]);
    b.ly1 = std::max(b.ly1, local.dy[k]);
    if (local.value[k] > 0.0f) {
      b.px0 = std::min(b.px0, local.dx[k]);
      b.px1 = std::max(b.px1, local.dx[k]);
      b.py0 = std::min(b.py0, local.dy[k]);
      b.py1 = std::max(b.py1, local.dy[k]);
    }
  }
  return b;
}

/// The map cells [cx0, cx1) x [cy0, cy1) the overlay shows.
struct CellBox {
  int cx0, cy0, cx1, cy1;
};

/// The echoes (positive cells) and the robot with 1 m around them, within the map and the
/// local grid (a scan's hits, not the whole of a large map), within the padding.
CellBox overlay_cells(const PaddedGrid& global, const LocalBounds& b, const Cell& robot,
                      double res) {
  const int pad = global.pad;
  const int margin = static_cast<int>(std::ceil(1.0 / res));
  const int cx0 = std::max({robot.ix + b.px0 - margin, std::min(0, robot.ix + b.lx0), -pad});
  const int cy0 = std::max({robot.iy + b.py0 - margin, std::min(0, robot.iy + b.ly0), -pad});
  const int cx1 = std::min({robot.ix + b.px1 + 1 + margin,
                            std::max(global.width, robot.ix + b.lx1 + 1), global.width + pad});
  const int cy1 = std::min({robot.iy + b.py1 + 1 + margin,
                            std::max(global.height, robot.iy + b.ly1 + 1), global.height + pad});
  return {cx0, cy0, cx1, cy1};
}

/// The local grid as a dense array over its bounds, row by row (0 where it has no cell).
std::vector<float> dense_local(const SparseLocalGrid& local, const LocalBounds& b) {
  const int lw = b.lx1 - b.lx0 + 1;
  std::vector<float> dense(static_cast<std::size_t>(lw) * (b.ly1 - b.ly0 + 1), 0.0f);
  for (std::size_t k = 0; k < local.size(); ++k) {
    dense[static_cast<std::size_t>(local.dy[k] - b.ly0) * lw + (local.dx[k] - b.lx0)] =
        local.value[k];
  }
  return dense;
}

/// The global grid in grey, the local grid's cells over it: positive ones orange (red on an
/// occupied cell), negative ones blue.
void paint_local_on_global(cv::Mat& img, const View& view, const PaddedGrid& global,
                           const std::vector<float>& dense, const LocalBounds& b, const Cell& robot,
                           double res) {
  const int pad = global.pad;
  const int lw = b.lx1 - b.lx0 + 1;
  for (int r = 0; r < view.height(); ++r) {
    auto* row = img.ptr<cv::Vec3b>(view.origin.y + r) + view.origin.x;
    for (int c = 0; c < view.width(); ++c) {
      const cv::Point2d p = view.at(c, r);
      const int ix = static_cast<int>(std::floor(p.x / res));
      const int iy = static_cast<int>(std::floor(p.y / res));
      float G = 0.0f;
      if (global.grid.geometry.contains(ix + pad, iy + pad)) G = global.grid.at(ix + pad, iy + pad);
      row[c] = grey(G > 0.0f ? kOccupiedGrey : (G < 0.0f ? kFreeGrey : kUnknownGrey));
      const int dx = ix - robot.ix - b.lx0, dy = iy - robot.iy - b.ly0;
      if (dx < 0 || dy < 0 || dx >= lw || dy > b.ly1 - b.ly0) continue;
      const float L = dense[static_cast<std::size_t>(dy) * lw + dx];
      if (L > 0.0f) row[c] = blend(G > 0.0f ? kArcOnWall : kArc, row[c], 0.9);
      if (L < 0.0f) row[c] = blend(kFreeCell, row[c], 0.42);
    }
  }
}

/// The map's edge, dashed, when the overlay reaches beyond it.
void draw_map_edge(cv::Mat& img, const View& view, const PaddedGrid& global, const CellBox& box,
                   double res) {
  if (box.cx0 < 0 || box.cy0 < 0 || box.cx1 > global.width || box.cy1 > global.height) {
    const cv::Point2d a = view.px(0.0, global.height * res), b = view.px(global.width * res, 0.0);
    const cv::Point2d corners[] = {a, {b.x, a.y}, b, {a.x, b.y}};
    for (int k = 0; k < 4; ++k) {
      plot::dashed_line(img, corners[k], corners[(k + 1) % 4], cv::Scalar(120, 120, 120), 1);
    }
  }
}

/// The robot's outline `footprint` at `world` (a 0.2 m circle when it has none).
void draw_outline(cv::Mat& img, const View& view, const GridGeometry& geometry,
                  const Footprint& footprint, const Pose2& world, const cv::Scalar& colour,
                  bool dashed) {
  const Pose2 p = geometry.to_grid_frame(world);
  const double c = std::cos(p.theta), s = std::sin(p.theta);
  std::vector<cv::Point2d> pts;
  for (const Eigen::Vector2d& q : footprint.polygon) {
    pts.push_back(view.px(p.x + c * q.x() - s * q.y(), p.y + s * q.x() + c * q.y()));
  }
  if (pts.empty()) {
    plot::circle(img, view.px(p.x, p.y), 0.2 * view.scale, colour, 2);
    return;
  }
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const cv::Point2d& u = pts[k];
    const cv::Point2d& w = pts[(k + 1) % pts.size()];
    if (dashed) {
      plot::dashed_line(img, u, w, colour, 2, 5.0);
    } else {
      plot::line(img, u, w, colour, 2);
    }
  }
}

/// A legend swatch: `colour` at opacity `alpha` over the free grey.
Symbol swatch(const cv::Vec3b& colour, double alpha) {
  return [colour, alpha](cv::Mat& m, const cv::Point2d& p) {
    const cv::Rect r(static_cast<int>(p.x) + 2, static_cast<int>(p.y) - 7, 24, 14);
    cv::Mat roi = m(r);
    roi = cv::Scalar(kFreeGrey, kFreeGrey, kFreeGrey);
    const cv::Vec3b c = blend(colour, grey(kFreeGrey), alpha);
    roi = cv::Scalar(c[0], c[1], c[2]);
    cv::rectangle(m, r, cv::Scalar(150, 150, 150), 1);
  };
}

/// The poses, the local grid's cells (negative ones when it has any) and the global grid's.
std::vector<plot::LegendItem> overlay_legend(const HeatmapMarks& marks,
                                             const SparseLocalGrid& local,
                                             const Footprint& footprint) {
  std::vector<plot::LegendItem> items = pose_legend(marks);
  const char* positive = footprint.polygon.empty() ? "local +: beam ends" : "local +: echo arcs";
  items.push_back({swatch(kArc, 0.9), positive});
  items.push_back({swatch(kArcOnWall, 0.9), std::string(positive) + " on an occupied cell"});
  if (std::any_of(local.value.begin(), local.value.end(), [](float x) { return x < 0.0f; })) {
    items.push_back({swatch(kFreeCell, 0.42), footprint.polygon.empty()
                                                  ? "local -: free space"
                                                  : "local -: free space, footprint"});
  }
  items.push_back({swatch(grey(kOccupiedGrey), 1.0), "global occupied"});
  items.push_back({swatch(grey(kUnknownGrey), 1.0), "global unknown"});
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
  draw_estimate_and_truth(img, view, volume.geometry, marks);
  draw_scale_and_axes(img, view, volume.geometry);
  const cv::Rect pr = view.rect();
  plot::colour_bar(img, lut, pr.x + pr.width + 22, pr.y, pr.y + pr.height, slice.lo, slice.hi,
                   "score S");
  title(img, score_xy_title(volume, max_over_headings), marks.caption);
  return legend_and_crop(img, score_xy_legend(marks), pr);
}

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

cv::Mat render_local_overlay(const PaddedGrid& global, const GridGeometry& geometry,
                             const SparseLocalGrid& local, const Cell& robot,
                             const Footprint& footprint, const HeatmapMarks& marks) {
  const double res = geometry.resolution;
  const LocalBounds bounds = local_bounds(local);
  const CellBox box = overlay_cells(global, bounds, robot, res);
  View view;
  view.x0 = box.cx0 * res;
  view.x1 = box.cx1 * res;
  view.y0 = box.cy0 * res;
  view.y1 = box.cy1 * res;
  view.scale = plot::fit_scale(view.x1 - view.x0, view.y1 - view.y0, res, 720.0);
  cv::Mat img = canvas(view, 30, kAxisBelow + 100, marks.caption);
  paint_local_on_global(img, view, global, dense_local(local, bounds), bounds, robot, res);
  draw_map_edge(img, view, global, box, res);
  // The robot's outline at the estimate (and the truth), then the pose markers.
  if (marks.truth) draw_outline(img, view, geometry, footprint, *marks.truth, plot::kTruth, true);
  draw_outline(img, view, geometry, footprint, marks.estimate, plot::kEstimate, false);
  draw_estimate_and_truth(img, view, geometry, marks);
  draw_scale_and_axes(img, view, geometry);
  title(img, "Local grid at the estimate, on the global grid", marks.caption);
  return legend_and_crop(img, overlay_legend(marks, local, footprint), view.rect());
}

}  // namespace gridloc::cli
