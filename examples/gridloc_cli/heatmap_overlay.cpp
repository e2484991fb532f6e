// The overlay image of `gridloc heatmap` (issue 4): the local grid at the estimate on the
// padded global grid, the robot's outline at the estimate and the truth.
#include "heatmap_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "heatmap_layout.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using layout::blend;
using layout::canvas;
using layout::draw_estimate_and_truth;
using layout::draw_scale_and_axes;
using layout::grey;
using layout::kAxisBelow;
using layout::kFreeGrey;
using layout::kOccupiedGrey;
using layout::kUnknownGrey;
using layout::legend_and_crop;
using layout::pose_legend;
using layout::title;
using plot::View;
using Symbol = decltype(plot::LegendItem::symbol);

cv::Vec3b to_vec(const cv::Scalar& s) {
  return {static_cast<std::uint8_t>(s[0]), static_cast<std::uint8_t>(s[1]),
          static_cast<std::uint8_t>(s[2])};
}

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
      if (global.grid.geometry.contains(ix + pad, iy + pad)) {
        G = global.cell(global.grid.geometry.index(ix + pad, iy + pad));
      }
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
