#include "heatmap_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "heatmap_plot.hpp"

namespace gridloc::cli {
namespace {

using plot::View;

constexpr int kLeft = 72;       // room for the y tick labels
constexpr int kTop = 104;       // title, two caption lines, the y axis label
constexpr int kAxisBelow = 56;  // x tick labels and axis label
constexpr double kHeatAlpha = 0.78;

// Grey levels of the map under the heat: free, occupied, unknown.
constexpr double kFreeGrey = 250.0, kOccupiedGrey = 60.0, kUnknownGrey = 200.0;

double infinity() {
  return std::numeric_limits<double>::infinity();
}

cv::Vec3b grey(double g) {
  const auto v = static_cast<std::uint8_t>(std::lround(g));
  return {v, v, v};
}

cv::Vec3b blend(const cv::Vec3b& top, const cv::Vec3b& under, double alpha) {
  cv::Vec3b out;
  for (int k = 0; k < 3; ++k) {
    out[k] = static_cast<std::uint8_t>(std::lround(alpha * top[k] + (1.0 - alpha) * under[k]));
  }
  return out;
}

cv::Vec3b to_vec(const cv::Scalar& s) {
  return {static_cast<std::uint8_t>(s[0]), static_cast<std::uint8_t>(s[1]),
          static_cast<std::uint8_t>(s[2])};
}

/// A white canvas with the plot area of `v` at (kLeft, kTop), `right` px beside it and
/// `below` px under it, wide enough for the caption's lines.
cv::Mat canvas(View& v, int right, int below, const std::string& caption) {
  v.origin = {kLeft, kTop};
  int width = kLeft + v.width() + right;
  std::istringstream lines(caption);
  for (std::string line; std::getline(lines, line);) {
    width = std::max(width, plot::text_size(line, plot::kTickScale).width + 24);
  }
  return cv::Mat(kTop + v.height() + below, width, CV_8UC3, cv::Scalar(255, 255, 255));
}

/// The title, then the caption's lines ('\n' separated).
void title(cv::Mat& img, const std::string& line1, const std::string& caption) {
  plot::text(img, line1, {12, 24}, plot::kTitleScale, plot::kInk, 2);
  std::istringstream lines(caption);
  std::string line;
  for (int y = 48; std::getline(lines, line); y += 20)
    plot::text(img, line, {12, y}, plot::kTickScale);
}

/// The canvas cut just below the legend's last row.
cv::Mat crop_below(const cv::Mat& img, int last_baseline) {
  return img.rowRange(0, std::min(img.rows, last_baseline + 16)).clone();
}

std::string pose_text(const Pose2& p) {
  std::ostringstream s;  // not "(" + std::string: GCC 12 warns falsely (-Wrestrict) on that
  s << "(" << plot::fixed(p.x, 2) << ", " << plot::fixed(p.y, 2) << " m, "
    << plot::fixed(rad2deg(p.theta), 1) << " deg)";
  return s.str();
}

/// The legend entries every map-like image shares.
std::vector<plot::LegendItem> pose_legend(const HeatmapMarks& marks) {
  std::vector<plot::LegendItem> items;
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) { plot::estimate_marker(m, p, 0.0); },
                   "estimate " + pose_text(marks.estimate)});
  if (marks.truth) {
    items.push_back({[](cv::Mat& m, const cv::Point2d& p) { plot::truth_marker(m, p, 0.0); },
                     "truth " + pose_text(*marks.truth)});
  }
  return items;
}

void draw_hypotheses(cv::Mat& img, const View& v, const GridGeometry& g,
                     const HeatmapMarks& marks) {
  // Lowest ranked first, so that the best lie on top.
  for (std::size_t k = marks.hypotheses.size(); k-- > 0;) {
    const Pose2 p = g.to_grid_frame(marks.hypotheses[k].pose);
    plot::hypothesis_marker(img, v.px(p.x, p.y), p.theta, static_cast<int>(k) + 1);
  }
}

void draw_estimate_and_truth(cv::Mat& img, const View& v, const GridGeometry& g,
                             const HeatmapMarks& marks) {
  if (marks.truth) {
    const Pose2 t = g.to_grid_frame(*marks.truth);
    plot::truth_marker(img, v.px(t.x, t.y), t.theta);
  }
  const Pose2 e = g.to_grid_frame(marks.estimate);
  plot::estimate_marker(img, v.px(e.x, e.y), e.theta);
}

std::string axis_name(const GridGeometry& g, const char* axis) {
  return std::string(g.yaw == 0.0 ? "" : "grid ") + axis + " (m)";
}

/// Tick label offsets: world coordinates when the grid is not rotated.
cv::Point2d tick_offset(const GridGeometry& g) {
  return g.yaw == 0.0 ? cv::Point2d(g.origin.x(), g.origin.y()) : cv::Point2d(0.0, 0.0);
}

/// The heading of a world angle on an axis of world headings centred on `centre` (rad).
double unwrap(double theta, double centre) {
  return centre + normalize_angle(theta - centre);
}

}  // namespace

cv::Mat render_score_xy(const ScoreVolume& volume, const OccupancyMap& map,
                        const HeatmapMarks& marks, bool max_over_headings) {
  const ScoreVolume& v = volume;
  const GridGeometry& g = v.geometry;
  const double res = v.resolution;
  std::vector<double> slice(static_cast<std::size_t>(v.nx) * v.ny, -infinity());
  for (int t = 0; t < v.headings; ++t) {
    if (!max_over_headings && t != v.best.it) continue;
    for (int y = 0; y < v.ny; ++y) {
      for (int x = 0; x < v.nx; ++x) {
        double& s = slice[static_cast<std::size_t>(y) * v.nx + x];
        s = std::max(s, v.at(x, y, t));
      }
    }
  }
  const auto [lo_it, hi_it] = std::minmax_element(slice.begin(), slice.end());
  const double lo = *lo_it, hi = *hi_it;

  // The window's cells and a margin around them (about 60 % of the window, 0.5 to 1.5 m),
  // the truth too, within the map.
  const double wx0 = v.ix0 * res, wx1 = (v.ix0 + v.nx) * res;
  const double wy0 = v.iy0 * res, wy1 = (v.iy0 + v.ny) * res;
  View view;
  const double margin = std::clamp(0.6 * std::max(wx1 - wx0, wy1 - wy0), 0.5, 1.5);
  view.x0 = wx0 - margin;
  view.x1 = wx1 + margin;
  view.y0 = wy0 - margin;
  view.y1 = wy1 + margin;
  if (marks.truth) {
    const Pose2 t = g.to_grid_frame(*marks.truth);
    view.x0 = std::min(view.x0, t.x - 0.5);
    view.x1 = std::max(view.x1, t.x + 0.5);
    view.y0 = std::min(view.y0, t.y - 0.5);
    view.y1 = std::max(view.y1, t.y + 0.5);
  }
  view.x0 = std::max(view.x0, 0.0);
  view.y0 = std::max(view.y0, 0.0);
  view.x1 = std::min(view.x1, g.width * res);
  view.y1 = std::min(view.y1, g.height * res);
  view.scale = plot::fit_scale(view.x1 - view.x0, view.y1 - view.y0, res, 640.0);
  cv::Mat img = canvas(view, 130, kAxisBelow + 100, marks.caption);

  // Map in grey, the score in viridis over it (semi-transparent: walls show through).
  const cv::Mat lut = plot::viridis();
  for (int r = 0; r < view.height(); ++r) {
    auto* row = img.ptr<cv::Vec3b>(view.origin.y + r) + view.origin.x;
    for (int c = 0; c < view.width(); ++c) {
      const cv::Point2d p = view.at(c, r);
      const Cell mc = map.geometry.cell_of(p.x, p.y);
      double gl = kUnknownGrey;
      if (map.geometry.contains(mc.ix, mc.iy)) {
        const CellState s = map.at(mc.ix, mc.iy);
        gl = s == CellState::Free ? kFreeGrey
                                  : (s == CellState::Occupied ? kOccupiedGrey : kUnknownGrey);
      }
      row[c] = grey(gl);
      const int x = static_cast<int>(std::floor(p.x / res)) - v.ix0;
      const int y = static_cast<int>(std::floor(p.y / res)) - v.iy0;
      if (x < 0 || y < 0 || x >= v.nx || y >= v.ny) continue;
      const double s = slice[static_cast<std::size_t>(y) * v.nx + x];
      const int k = hi > lo ? static_cast<int>(std::lround(255.0 * (s - lo) / (hi - lo))) : 255;
      row[c] = blend(lut.at<cv::Vec3b>(k), row[c], kHeatAlpha);
    }
  }

  // The search window (clipped to the map), dark then white so that it shows on any colour.
  const cv::Point2d a = view.px(wx0, wy1), b = view.px(wx1, wy0);
  cv::rectangle(img, plot::sub(a), plot::sub(b), plot::kInk, 3, cv::LINE_AA, plot::kShift);
  cv::rectangle(img, plot::sub(a), plot::sub(b), plot::kWindow, 1, cv::LINE_AA, plot::kShift);
  draw_hypotheses(img, view, g, marks);
  draw_estimate_and_truth(img, view, g, marks);
  plot::scale_bar(img, view);
  const cv::Point2d o = tick_offset(g);
  plot::axes_m(img, view, o.x, o.y, axis_name(g, "x"), axis_name(g, "y"));
  const cv::Rect pr = view.rect();
  plot::colour_bar(img, lut, pr.x + pr.width + 22, pr.y, pr.y + pr.height, lo, hi, "score S");

  const double best_deg = rad2deg(v.theta0 + g.yaw + v.best.it * v.step_theta);
  title(img,
        max_over_headings
            ? "Score S over x, y: maximum over the " + std::to_string(v.headings) + " headings"
            : "Score S over x, y at the best heading, " + plot::fixed(best_deg, 1) + " deg",
        marks.caption);
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
  const int last = plot::legend(img, items, 12, pr.y + pr.height + kAxisBelow + 20, img.cols - 8);
  return crop_below(img, last);
}

cv::Mat render_score_theta(const ScoreVolume& volume, const HeatmapMarks& marks) {
  const ScoreVolume& v = volume;
  const double yaw = v.geometry.yaw;
  std::vector<double> curve(static_cast<std::size_t>(v.headings), -infinity());
  for (int t = 0; t < v.headings; ++t) {
    for (int y = 0; y < v.ny; ++y) {
      for (int x = 0; x < v.nx; ++x) curve[t] = std::max(curve[t], v.at(x, y, t));
    }
  }
  auto heading = [&](double t) { return v.theta0 + yaw + t * v.step_theta; };  // world, rad
  const double centre = heading(0.5 * (v.headings - 1));
  double xlo = rad2deg(heading(0)), xhi = rad2deg(heading(v.headings - 1));
  const double xpad = std::max(0.02 * (xhi - xlo), 0.5 * rad2deg(v.step_theta));
  xlo -= xpad;
  xhi += xpad;
  auto [lo_it, hi_it] = std::minmax_element(curve.begin(), curve.end());
  double ylo = *lo_it, yhi = *hi_it;
  for (const Hypothesis& h : marks.hypotheses) ylo = std::min(ylo, h.score);
  const double ypad = yhi > ylo ? 0.1 * (yhi - ylo) : 1.0;
  ylo -= ypad;
  yhi += ypad;

  constexpr int kW = 760, kH = 330;
  View frame;  // only for the canvas: kW x kH px
  frame.x1 = kW;
  frame.y1 = kH;
  frame.scale = 1.0;
  cv::Mat img = canvas(frame, 30, kAxisBelow + 80, marks.caption);
  const cv::Rect pr(kLeft, kTop, kW, kH);
  auto fx = [&](double deg) { return pr.x + (deg - xlo) / (xhi - xlo) * pr.width; };
  auto fy = [&](double s) { return pr.y + (yhi - s) / (yhi - ylo) * pr.height; };

  // Grid lines and ticks: headings at round degrees, scores at 1-2-5 steps.
  double xstep = 1.0;
  for (double s : {1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0}) {
    xstep = s;
    if (s * pr.width / (xhi - xlo) >= 60.0) break;
  }
  const double ystep = plot::nice_step((yhi - ylo) / 6.0);
  const int ydigits = ystep >= 1.0 ? 0 : (ystep >= 0.1 ? 1 : 2);
  for (double d = std::ceil(xlo / xstep) * xstep; d <= xhi; d += xstep) {
    const double x = fx(d);
    plot::line(img, {x, static_cast<double>(pr.y)}, {x, static_cast<double>(pr.y + pr.height)},
               plot::kGridLine, 1);
    const std::string s = plot::fixed(d, 0);
    const cv::Size ts = plot::text_size(s, plot::kTickScale);
    plot::text(img, s,
               {static_cast<int>(std::lround(x)) - ts.width / 2, pr.y + pr.height + 8 + ts.height},
               plot::kTickScale);
  }
  for (double s = std::ceil(ylo / ystep) * ystep; s <= yhi; s += ystep) {
    const double y = fy(s);
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

  // Truth and estimate headings as vertical lines, labelled inside the plot.
  auto vertical = [&](double theta, const cv::Scalar& colour, bool dashed, const std::string& label,
                      int row) {
    const double x = fx(rad2deg(unwrap(theta, centre)));
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
  };
  vertical(marks.estimate.theta, plot::kEstimate, false,
           "estimate " + plot::fixed(rad2deg(marks.estimate.theta), 1), 0);

  if (marks.truth) {
    vertical(marks.truth->theta, plot::kTruth, true,
             "truth " + plot::fixed(rad2deg(marks.truth->theta), 1), 1);
  }
  // The curve, a dot per heading when they are far enough apart.
  const cv::Scalar kCurve(170, 90, 20);
  std::vector<cv::Point> pts;
  for (int t = 0; t < v.headings; ++t)
    pts.push_back(plot::sub({fx(rad2deg(heading(t))), fy(curve[t])}));
  cv::polylines(img, pts, false, kCurve, 2, cv::LINE_AA, plot::kShift);
  if (pr.width / std::max(1, v.headings) >= 6) {
    for (const cv::Point& p : pts)
      cv::circle(img, p, 3 << plot::kShift, kCurve, cv::FILLED, cv::LINE_AA, plot::kShift);
  }
  for (std::size_t k = marks.hypotheses.size(); k-- > 0;) {
    const Hypothesis& h = marks.hypotheses[k];
    const double x = fx(rad2deg(unwrap(h.pose.theta, centre)));
    if (x < pr.x || x > pr.x + pr.width) continue;
    plot::hypothesis_marker(img, {x, fy(h.score)}, std::nan(""), static_cast<int>(k) + 1);
  }

  title(img, "Score against heading: the best S over x, y at each heading", marks.caption);
  std::vector<plot::LegendItem> items = {
      {[&](cv::Mat& m, const cv::Point2d& p) {
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
  const int last = plot::legend(img, items, 12, pr.y + pr.height + kAxisBelow + 20, img.cols - 8);
  return crop_below(img, last);
}

cv::Mat render_local_overlay(const PaddedGrid& global, const GridGeometry& geometry,
                             const SparseLocalGrid& local, const Cell& robot,
                             const Footprint& footprint, const HeatmapMarks& marks) {
  const double res = geometry.resolution;
  const int pad = global.pad;
  // The echoes (positive cells) and the robot with 1 m around them, within the map and the
  // local grid (a scan's hits, not the whole of a large map), within the padding.
  int lx0 = 0, ly0 = 0, lx1 = 0, ly1 = 0;  // local bounds, inclusive
  int px0 = 0, py0 = 0, px1 = 0, py1 = 0;  // bounds of the positive cells and the robot
  for (std::size_t k = 0; k < local.size(); ++k) {
    lx0 = std::min(lx0, local.dx[k]);
    lx1 = std::max(lx1, local.dx[k]);
    ly0 = std::min(ly0, local.dy[k]);
    ly1 = std::max(ly1, local.dy[k]);
    if (local.value[k] > 0.0f) {
      px0 = std::min(px0, local.dx[k]);
      px1 = std::max(px1, local.dx[k]);
      py0 = std::min(py0, local.dy[k]);
      py1 = std::max(py1, local.dy[k]);
    }
  }
  const int margin = static_cast<int>(std::ceil(1.0 / res));
  const int cx0 = std::max({robot.ix + px0 - margin, std::min(0, robot.ix + lx0), -pad});
  const int cy0 = std::max({robot.iy + py0 - margin, std::min(0, robot.iy + ly0), -pad});
  const int cx1 = std::min({robot.ix + px1 + 1 + margin, std::max(global.width, robot.ix + lx1 + 1),
                            global.width + pad});
  const int cy1 = std::min({robot.iy + py1 + 1 + margin,
                            std::max(global.height, robot.iy + ly1 + 1), global.height + pad});
  const int lw = lx1 - lx0 + 1;
  std::vector<float> dense(static_cast<std::size_t>(lw) * (ly1 - ly0 + 1), 0.0f);
  for (std::size_t k = 0; k < local.size(); ++k) {
    dense[static_cast<std::size_t>(local.dy[k] - ly0) * lw + (local.dx[k] - lx0)] = local.value[k];
  }

  View view;
  view.x0 = cx0 * res;
  view.x1 = cx1 * res;
  view.y0 = cy0 * res;
  view.y1 = cy1 * res;
  view.scale = plot::fit_scale(view.x1 - view.x0, view.y1 - view.y0, res, 720.0);
  cv::Mat img = canvas(view, 30, kAxisBelow + 100, marks.caption);

  const cv::Vec3b arc_on_wall = to_vec(cv::Scalar(0, 0, 200));   // red
  const cv::Vec3b arc = to_vec(cv::Scalar(0, 150, 255));         // orange
  const cv::Vec3b free_cell = to_vec(cv::Scalar(235, 140, 40));  // blue
  for (int r = 0; r < view.height(); ++r) {
    auto* row = img.ptr<cv::Vec3b>(view.origin.y + r) + view.origin.x;
    for (int c = 0; c < view.width(); ++c) {
      const cv::Point2d p = view.at(c, r);
      const int ix = static_cast<int>(std::floor(p.x / res));
      const int iy = static_cast<int>(std::floor(p.y / res));
      float G = 0.0f;
      if (global.grid.geometry.contains(ix + pad, iy + pad)) G = global.grid.at(ix + pad, iy + pad);
      row[c] = grey(G > 0.0f ? kOccupiedGrey : (G < 0.0f ? kFreeGrey : kUnknownGrey));
      const int dx = ix - robot.ix - lx0, dy = iy - robot.iy - ly0;
      if (dx < 0 || dy < 0 || dx >= lw || dy > ly1 - ly0) continue;
      const float L = dense[static_cast<std::size_t>(dy) * lw + dx];
      if (L > 0.0f) row[c] = blend(G > 0.0f ? arc_on_wall : arc, row[c], 0.9);
      if (L < 0.0f) row[c] = blend(free_cell, row[c], 0.42);
    }
  }
  // The map's edge when the local grid reaches beyond it.
  if (cx0 < 0 || cy0 < 0 || cx1 > global.width || cy1 > global.height) {  // beyond the map
    const cv::Point2d a = view.px(0.0, global.height * res), b = view.px(global.width * res, 0.0);
    const cv::Point2d corners[] = {a, {b.x, a.y}, b, {a.x, b.y}};
    for (int k = 0; k < 4; ++k) {
      plot::dashed_line(img, corners[k], corners[(k + 1) % 4], cv::Scalar(120, 120, 120), 1);
    }
  }

  // The robot's outline at the estimate (and the truth), then the pose markers.
  auto outline = [&](const Pose2& world, const cv::Scalar& colour, bool dashed) {
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
  };
  if (marks.truth) outline(*marks.truth, plot::kTruth, true);
  outline(marks.estimate, plot::kEstimate, false);
  draw_estimate_and_truth(img, view, geometry, marks);
  plot::scale_bar(img, view);
  const cv::Point2d o = tick_offset(geometry);
  plot::axes_m(img, view, o.x, o.y, axis_name(geometry, "x"), axis_name(geometry, "y"));

  title(img, "Local grid at the estimate, on the global grid", marks.caption);
  auto swatch = [](const cv::Vec3b& colour, double alpha) {
    return [colour, alpha](cv::Mat& m, const cv::Point2d& p) {
      const cv::Rect r(static_cast<int>(p.x) + 2, static_cast<int>(p.y) - 7, 24, 14);
      cv::Mat roi = m(r);
      roi = cv::Scalar(kFreeGrey, kFreeGrey, kFreeGrey);
      const cv::Vec3b c = blend(colour, grey(kFreeGrey), alpha);
      roi = cv::Scalar(c[0], c[1], c[2]);
      cv::rectangle(m, r, cv::Scalar(150, 150, 150), 1);
    };
  };
  std::vector<plot::LegendItem> items = pose_legend(marks);
  const char* positive = footprint.polygon.empty() ? "local +: beam ends" : "local +: echo arcs";
  items.push_back({swatch(arc, 0.9), positive});
  items.push_back({swatch(arc_on_wall, 0.9), std::string(positive) + " on an occupied cell"});
  if (std::any_of(local.value.begin(), local.value.end(), [](float x) { return x < 0.0f; })) {
    items.push_back({swatch(free_cell, 0.42), footprint.polygon.empty()
                                                  ? "local -: free space"
                                                  : "local -: free space, footprint"});
  }
  items.push_back({swatch(grey(kOccupiedGrey), 1.0), "global occupied"});
  items.push_back({swatch(grey(kUnknownGrey), 1.0), "global unknown"});
  const cv::Rect pr = view.rect();
  const int last = plot::legend(img, items, 12, pr.y + pr.height + kAxisBelow + 20, img.cols - 8);
  return crop_below(img, last);
}

}  // namespace gridloc::cli
