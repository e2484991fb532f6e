#include "disambiguation_render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "disambiguation_marks.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/error.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using plot::Box;
using plot::Contours;
using plot::fill_rings;
using plot::filled;
using plot::outline_rings;
using plot::stroke;
using plot::View;
using plot::wrap;
using namespace disambiguation_marks;

constexpr int kLeft = 72;        // room for the y tick labels, left of either panel
constexpr int kRight = 28;       // the right frame clear of the canvas
constexpr int kAxisBelow = 56;   // x tick labels and axis label
constexpr int kMaxWidth = 1800;  // the whole image
constexpr int kPlotBudget = kMaxWidth - 2 * kLeft - kRight;  // both plot areas side by side
constexpr int kMaxPlotHeight = 900;                          // either plot area
constexpr int kMinPanelWidth = 400;   // a plot area at least this wide (its heading fits)
constexpr int kMinPanelHeight = 200;  // and this high
constexpr int kHeadingClear = 130;    // heading lines end this far left of the plot's right edge
                                      // (the next panel's y axis label reaches over it)
constexpr int kMinCommonPx = 300;     // a common scale leaves each panel's longer side this long
constexpr double kMarginFraction = 0.05;  // beyond the drawn things, of the longer side

/// A plot area and the round world offset subtracted from the coordinates it shows.
struct Panel {
  View view;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  int offset_power = 0;  ///< the offset is a multiple of 10^offset_power

  /// Canvas pixel of a point of the panel's frame.
  cv::Point2d at(const Eigen::Vector2d& p) const {
    return view.px(p.x() - offset.x(), p.y() - offset.y());
  }
  /// The same panel drawn into its own plot area (img(view.rect())).
  Panel local() const {
    Panel p = *this;
    p.view.origin = {0, 0};
    return p;
  }
};

/// The box grown by kMarginFraction of its longer side on each side.
Box padded(const Box& box) {
  return plot::padded(box, kMarginFraction);
}

/// Sets a round offset when the coordinates are large beside the box (far from the origin),
/// so that tick labels stay short; zero otherwise.
void set_axis_offset(Panel& panel, const Box& box) {
  const double side = (box.hi - box.lo).maxCoeff();
  const double far = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  if (far < 1e4 || far < 100.0 * side) return;
  const int power = static_cast<int>(std::ceil(std::log10(side)));
  const double unit = std::pow(10.0, power);
  const Eigen::Vector2d centre = 0.5 * (box.lo + box.hi);
  panel.offset = (centre / unit).array().round().matrix() * unit;
  panel.offset_power = power;
}

/// A panel showing `box` (padded) at `scale` px/m, grown to kMinPanelWidth x kMinPanelHeight
/// px about its centre.
Panel make_panel(const Box& box, double scale) {
  Panel panel;
  set_axis_offset(panel, box);
  const Eigen::Vector2d size = box.hi - box.lo;
  const double extra_x = std::max(0.0, kMinPanelWidth / scale - size.x()) / 2.0;
  const double extra_y = std::max(0.0, kMinPanelHeight / scale - size.y()) / 2.0;
  panel.view.x0 = box.lo.x() - extra_x - panel.offset.x();
  panel.view.x1 = box.hi.x() + extra_x - panel.offset.x();
  panel.view.y0 = box.lo.y() - extra_y - panel.offset.y();
  panel.view.y1 = box.hi.y() + extra_y - panel.offset.y();
  panel.view.scale = scale;
  return panel;
}

/// The scales (px/m) of the two panels: one common scale when it leaves each panel's longer
/// side at least kMinCommonPx, else each fitted into half the width.
std::pair<double, double> panel_scales(const Box& start, const Box& world) {
  const Eigen::Vector2d a = start.hi - start.lo, b = world.hi - world.lo;
  double common = std::min(kPlotBudget / (a.x() + b.x()), kMaxPlotHeight / std::max(a.y(), b.y()));
  // The narrower panel may be widened to kMinPanelWidth: leave it room.
  common = std::min(common, (kPlotBudget - kMinPanelWidth) / std::max(a.x(), b.x()));
  if (std::min(a.maxCoeff(), b.maxCoeff()) * common >= kMinCommonPx) return {common, common};
  const auto fitted = [](const Eigen::Vector2d& e) {
    return std::min(0.5 * kPlotBudget / e.x(), kMaxPlotHeight / e.y());
  };
  return {fitted(a), fitted(b)};
}

/// What the left panel shows (start frame): every map, OI, U, the points, the path.
Box start_box(const DisambiguationPicture& picture) {
  Box box;
  box.add(Eigen::Vector2d::Zero());
  for (const Area& map : picture.overlay.maps) box.add(map.outer);
  box.add(picture.overlay.oi.outer);
  for (const Area& area : picture.useful) box.add(area.outer);
  box.add(picture.samples);
  box.add(picture.path);
  box.add(picture.stops);
  if (picture.bound_point) box.add(*picture.bound_point);
  return box;
}

/// What the right panel shows (world): the map, the hypotheses, the paths under those standing.
Box world_box(const DisambiguationPicture& picture) {
  Box box;
  box.add(picture.map.boundary);
  for (const Pose2& h : picture.hypotheses) box.add(Eigen::Vector2d(h.x, h.y));
  for (const int i : picture.remaining) {
    for (const Eigen::Vector2d& p : picture.path) box.add(to_world(picture.hypotheses[i], p));
  }
  return box;
}

/// A ring as sub-pixel OpenCV points (plot::kShift); empty when a vertex is not finite.
std::vector<cv::Point> contour(const Polygon& ring, const Panel& panel) {
  std::vector<cv::Point> points;
  for (const Eigen::Vector2d& v : ring) {
    if (!v.allFinite()) return {};
    points.push_back(plot::sub(panel.at(v)));
  }
  return points;
}

/// The rings of an area (outer and holes) as contours.
Contours area_contours(const Area& area, const Panel& panel) {
  Contours rings{contour(area.outer, panel)};
  for (const Polygon& hole : area.holes) rings.push_back(contour(hole, panel));
  return rings;
}

/// An open polyline through the finite points.
void polyline(cv::Mat& img, const std::vector<Eigen::Vector2d>& points, const Panel& panel,
              const cv::Scalar& colour, int thickness) {
  std::vector<cv::Point> line;
  for (const Eigen::Vector2d& p : points) {
    if (p.allFinite()) line.push_back(plot::sub(panel.at(p)));
  }
  if (line.size() < 2) return;
  cv::polylines(img, Contours{line}, false, colour, thickness, cv::LINE_AA, plot::kShift);
}

void draw_segments(cv::Mat& img, const std::vector<PlanarSegment>& segments, const Panel& panel,
                   const cv::Scalar& colour, int thickness) {
  for (const PlanarSegment& s : segments) {
    if (s.a.allFinite() && s.b.allFinite()) {
      plot::line(img, panel.at(s.a), panel.at(s.b), colour, thickness);
    }
  }
}

/// The index in picture.hypotheses of the overlay's map `k` (its pose found there; else k), so
/// that a map and its hypothesis share their colour.
int hypothesis_of_map(const DisambiguationPicture& picture, std::size_t k) {
  if (k < picture.overlay.hypotheses.size()) {
    const Pose2& h = picture.overlay.hypotheses[k];
    for (std::size_t i = 0; i < picture.hypotheses.size(); ++i) {
      const Pose2& g = picture.hypotheses[i];
      if (g.x == h.x && g.y == h.y && g.theta == h.theta) return static_cast<int>(i);
    }
  }
  return static_cast<int>(k);
}

/// OI filled, U blended over it with its outline (seed 002 Figs 4 and 7).
void paint_oi_and_useful(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  if (!picture.overlay.oi.outer.empty()) {
    fill_rings(img, area_contours(picture.overlay.oi, panel), kOiFill);
  }
  if (picture.useful.empty()) return;
  cv::Mat layer = img.clone();
  for (const Area& area : picture.useful)
    fill_rings(layer, area_contours(area, panel), kUsefulFill);
  cv::addWeighted(layer, kUsefulAlpha, img, 1.0 - kUsefulAlpha, 0.0, img);
  for (const Area& area : picture.useful) {
    outline_rings(img, area_contours(area, panel), kUsefulEdge, 1);
  }
}

/// Every hypothesis's map outlined in its colour (seed 002 Fig. 3), then OI's edges: internal
/// thick orange, silhouette dark (Fig. 5).
void paint_overlay_edges(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  const int thickness = picture.overlay.maps.size() <= 12 ? 2 : 1;
  for (std::size_t k = 0; k < picture.overlay.maps.size(); ++k) {
    outline_rings(img, area_contours(picture.overlay.maps[k], panel),
                  hypothesis_colour(hypothesis_of_map(picture, k)), thickness);
  }
  draw_segments(img, picture.overlay.silhouette_edges, panel, kSilhouette, 2);
  draw_segments(img, picture.overlay.internal_edges, panel, kInternalEdge, 4);
}

/// The random points, the path (Fig. 17) with its numbered stops, the start, the bound point.
void paint_samples_and_path(cv::Mat& img, const DisambiguationPicture& picture,
                            const Panel& panel) {
  for (const Eigen::Vector2d& p : picture.samples) {
    if (p.allFinite()) sample_dot(img, panel.at(p));
  }
  polyline(img, picture.path, panel, plot::kWhite, 6);
  polyline(img, picture.path, panel, kPath, 3);
  for (std::size_t k = 0; k < picture.stops.size(); ++k) {
    if (picture.stops[k].allFinite()) {
      stop_marker(img, panel.at(picture.stops[k]), static_cast<int>(k) + 1);
    }
  }
  if (picture.bound_point && picture.bound_point->allFinite()) {
    bound_marker(img, panel.at(*picture.bound_point));
  }
  start_marker(img, panel.at(Eigen::Vector2d::Zero()));
}

/// The left panel: the overlay in the start frame (seed 002 Figs 3, 4, 7, 17).
void paint_start_panel(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  cv::Mat area = img(panel.view.rect());
  const Panel local = panel.local();
  paint_oi_and_useful(area, picture, local);
  paint_overlay_edges(area, picture, local);
  paint_samples_and_path(area, picture, local);
  plot::scale_bar(img, panel.view);
}

/// The map: outside and obstacles grey, free space white, walls dark.
void paint_map(cv::Mat& img, const PolygonMap& map, const Panel& panel) {
  img.setTo(kOutside);
  Contours rings{contour(map.boundary, panel)};
  for (const Polygon& obstacle : map.obstacles) rings.push_back(contour(obstacle, panel));
  if (rings.front().empty()) return;
  fill_rings(img, rings, plot::kWhite);
  outline_rings(img, rings, kSilhouette, 2);
}

/// The path and its stops under each standing hypothesis, in that hypothesis's colour.
void paint_world_paths(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  for (const int i : picture.remaining) {
    const Pose2& h = picture.hypotheses[i];
    std::vector<Eigen::Vector2d> path, stops;
    for (const Eigen::Vector2d& p : picture.path) path.push_back(to_world(h, p));
    for (const Eigen::Vector2d& p : picture.stops) stops.push_back(to_world(h, p));
    polyline(img, path, panel, plot::kWhite, 6);
    polyline(img, path, panel, hypothesis_colour(i), 3);
    for (const Eigen::Vector2d& p : stops) {
      if (!p.allFinite()) continue;
      plot::circle(img, panel.at(p), 4.0, plot::kWhite, cv::FILLED);
      plot::circle(img, panel.at(p), 4.0, hypothesis_colour(i), 2);
    }
  }
}

/// Whether every field of the pose is finite (else it is not drawn).
bool finite(const Pose2& h) {
  return std::isfinite(h.x) && std::isfinite(h.y) && std::isfinite(h.theta);
}

/// Every hypothesis (with a finite pose) numbered by its index: the eliminated faded, the
/// standing ringed in their colour, then the truth.
void paint_hypotheses(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  std::vector<bool> standing(picture.hypotheses.size(), false);
  for (const int i : picture.remaining) standing[i] = true;
  for (std::size_t i = 0; i < picture.hypotheses.size(); ++i) {
    const Pose2& h = picture.hypotheses[i];
    if (!standing[i] && finite(h)) {
      faded_marker(img, panel.at({h.x, h.y}), h.theta, static_cast<int>(i));
    }
  }
  for (const int i : picture.remaining) {
    const Pose2& h = picture.hypotheses[i];
    if (!finite(h)) continue;
    plot::circle(img, panel.at({h.x, h.y}), 9.0, hypothesis_colour(i), 3);
    plot::hypothesis_marker(img, panel.at({h.x, h.y}), h.theta, i);
  }
  const int truth = picture.true_hypothesis;
  if (truth >= 0 && finite(picture.hypotheses[truth])) {
    const Pose2& h = picture.hypotheses[truth];
    plot::truth_marker(img, panel.at({h.x, h.y}), h.theta);
  }
}

/// The right panel: the map in the world with the hypotheses and the paths.
void paint_world_panel(cv::Mat& img, const DisambiguationPicture& picture, const Panel& panel) {
  cv::Mat area = img(panel.view.rect());
  const Panel local = panel.local();
  paint_map(area, picture.map, local);
  paint_world_paths(area, picture, local);
  paint_hypotheses(area, picture, local);
}

/// The axis labels of a panel: "x (m)", or with the offset subtracted from large coordinates
/// "x - 1.5e+09 (m)", written with the significant digits of a multiple of 10^offset_power.
std::pair<std::string, std::string> axis_labels(const Panel& panel) {
  const auto label = [&](const char* axis, double offset) {
    if (offset == 0.0) return std::string(axis) + " (m)";
    const int digits =
        static_cast<int>(std::floor(std::log10(std::abs(offset)))) + 1 - panel.offset_power;
    std::array<char, 64> buffer{};
    std::snprintf(buffer.data(), buffer.size(), "%.*g", std::clamp(digits, 1, 17),
                  std::abs(offset));
    return std::string(axis) + (offset < 0.0 ? " + " : " - ") + buffer.data() + " (m)";
  };
  return {label("x", panel.offset.x()), label("y", panel.offset.y())};
}

/// The two heading lines of the left panel.
std::vector<std::string> start_heading(const DisambiguationPicture& picture) {
  const std::size_t maps = picture.overlay.maps.size();
  std::string facts = std::to_string(maps) + (maps == 1 ? " map" : " maps") + " overlaid, " +
                      (picture.useful.empty() ? "U empty, " : "") +
                      std::to_string(picture.samples.size()) + " random points, " +
                      std::to_string(picture.stops.size()) +
                      (picture.stops.size() == 1 ? " stop" : " stops");
  if (picture.path.size() < 2) facts += ", no path";
  return {"Start frame: the overlay of the first stop (seed 002 Figs 3, 4, 7, 17)", facts};
}

/// The two heading lines of the right panel.
std::vector<std::string> world_heading(const DisambiguationPicture& picture) {
  const std::size_t n = picture.hypotheses.size();
  std::string facts = std::to_string(n) + (n == 1 ? " hypothesis, " : " hypotheses, ") +
                      std::to_string(picture.remaining.size()) +
                      " standing (the path under each, in its map's colour)";
  if (picture.true_hypothesis >= 0) facts += ", truth " + std::to_string(picture.true_hypothesis);
  return {"World: the map and the hypotheses (numbered by index)", facts};
}

/// A panel's heading lines above its plot area, the last one ending 8 px above it.
void draw_heading(cv::Mat& img, const Panel& panel, const std::vector<std::string>& heading) {
  const cv::Rect r = panel.view.rect();
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < heading.size(); ++k) {
    for (const std::string& l : wrap(heading[k], plot::kTickScale, 1, r.width - kHeadingClear)) {
      lines.push_back(l);
    }
  }
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int y = r.y - 8 - 20 * static_cast<int>(lines.size() - 1 - k);
    plot::text(img, lines[k], {r.x, y}, plot::kTickScale, plot::kInk, k == 0 ? 2 : 1);
  }
}

/// The number of lines a panel heading takes at `width` px.
int heading_lines(const std::vector<std::string>& heading, int width) {
  int n = 0;
  for (const std::string& line : heading) {
    n += static_cast<int>(wrap(line, plot::kTickScale, 1, width - kHeadingClear).size());
  }
  return n;
}

/// The left panel's items.
std::vector<plot::LegendItem> start_legend(const DisambiguationPicture& picture) {
  std::vector<plot::LegendItem> items;
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     for (int k = 0; k < 3; ++k) {
                       const cv::Point2d y(0.0, 4.0 * (k - 1));
                       plot::line(m, p + y, p + y + cv::Point2d(26, 0), hypothesis_colour(k), 2);
                     }
                   },
                   "each hypothesis's map (its colour on both panels)"});
  items.push_back(filled(kOiFill, "OI: the overlay intersection holding the start"));
  const cv::Scalar useful = kUsefulFill * kUsefulAlpha + kOiFill * (1.0 - kUsefulAlpha);
  items.push_back(filled(useful, "U: the useful region"));
  items.push_back(stroke(kInternalEdge, 4, "OI's internal edges"));
  items.push_back(stroke(kSilhouette, 2, "OI's silhouette edges"));
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     for (int k = 0; k < 4; ++k) {
                       sample_dot(m, p + cv::Point2d(3 + 7 * k, k % 2 ? 3 : -3));
                     }
                   },
                   "random points"});
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     plot::line(m, p, p + cv::Point2d(26, 0), kPath, 3);
                     stop_marker(m, p + cv::Point2d(26, 0), 0);
                   },
                   "path and its stops (numbered)"});
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) { start_marker(m, p + cv::Point2d(8, 0)); },
                   "start (origin)"});
  if (picture.bound_point) {
    items.push_back(
        {[](cv::Mat& m, const cv::Point2d& p) { bound_marker(m, p + cv::Point2d(8, 0)); },
         "the lower bound's nearest informative point"});
  }
  return items;
}

/// The right panel's items.
std::vector<plot::LegendItem> world_legend(const DisambiguationPicture& picture) {
  std::vector<plot::LegendItem> items;
  items.push_back(filled(plot::kWhite, "free space"));
  items.push_back(filled(kOutside, "outside, obstacles"));
  items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                     plot::circle(m, p + cv::Point2d(14, 0), 9.0, hypothesis_colour(0), 3);
                     plot::hypothesis_marker(m, p + cv::Point2d(14, 0), 0.0, 0);
                   },
                   "standing hypothesis, its heading"});
  items.push_back(
      {[](cv::Mat& m, const cv::Point2d& p) { faded_marker(m, p + cv::Point2d(14, 0), 0.0, 1); },
       "eliminated"});
  if (picture.true_hypothesis >= 0) {
    items.push_back({[](cv::Mat& m, const cv::Point2d& p) {
                       plot::truth_marker(m, p + cv::Point2d(8, 0), 0.0);
                     },
                     "the truth"});
  }
  return items;
}

/// Throws gridloc::Error when an index names no hypothesis.
void check_indices(const DisambiguationPicture& picture) {
  const int n = static_cast<int>(picture.hypotheses.size());
  for (const int i : picture.remaining) {
    if (i < 0 || i >= n) {
      throw Error("disambiguation picture: remaining hypothesis " + std::to_string(i) +
                  " is not one of the " + std::to_string(n) + " hypotheses");
    }
  }
  if (picture.true_hypothesis < -1 || picture.true_hypothesis >= n) {
    throw Error("disambiguation picture: true hypothesis " +
                std::to_string(picture.true_hypothesis) + " is not one of the " +
                std::to_string(n) + " hypotheses");
  }
}

/// The two panels placed side by side below the title, caption and headings.
struct Layout {
  Panel start, world;
  std::vector<std::string> title, caption;
  int width = 0;
};

/// The panels' scales and places, the title and caption wrapped to the image's width.
Layout make_layout(const DisambiguationPicture& picture) {
  const Box start = padded(start_box(picture)), world = padded(world_box(picture));
  const auto [start_scale, world_scale] = panel_scales(start, world);
  Layout layout{make_panel(start, start_scale), make_panel(world, world_scale), {}, {}, 0};
  const int start_w = layout.start.view.width(), world_w = layout.world.view.width();
  layout.width = kLeft + start_w + kLeft + world_w + kRight;
  layout.title = wrap(picture.title, plot::kTitleScale, 2, layout.width - 24);
  layout.caption = wrap(picture.caption, plot::kTickScale, 1, layout.width - 24);
  const int lines = std::max(heading_lines(start_heading(picture), start_w),
                             heading_lines(world_heading(picture), world_w));
  const int top =
      plot::title_block_bottom(layout.title.size(), layout.caption.size()) + 20 * lines + 4;
  layout.start.view.origin = {kLeft, top};
  layout.world.view.origin = {kLeft + start_w + kLeft, top};
  return layout;
}

}  // namespace

cv::Mat render_disambiguation(const DisambiguationPicture& picture) {
  check_indices(picture);
  const Layout layout = make_layout(picture);
  const int plots_bottom =
      std::max(layout.start.view.rect().br().y, layout.world.view.rect().br().y);
  cv::Mat img(plots_bottom + kAxisBelow + 260, layout.width, CV_8UC3, plot::kWhite);
  paint_start_panel(img, picture, layout.start);
  paint_world_panel(img, picture, layout.world);
  const auto [sx, sy] = axis_labels(layout.start);
  plot::axes_m(img, layout.start.view, 0.0, 0.0, sx, sy);
  const auto [wx, wy] = axis_labels(layout.world);
  plot::axes_m(img, layout.world.view, 0.0, 0.0, wx, wy);
  plot::title_block(img, layout.title, layout.caption);
  draw_heading(img, layout.start, start_heading(picture));
  draw_heading(img, layout.world, world_heading(picture));
  std::vector<plot::LegendItem> items = start_legend(picture);
  for (plot::LegendItem& item : world_legend(picture)) items.push_back(std::move(item));
  const int last = plot::legend(img, items, 12, plots_bottom + kAxisBelow + 20, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
