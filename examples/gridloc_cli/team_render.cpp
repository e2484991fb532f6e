// The image of `gridloc team` (seed 003 ch. V, Figs 13, 14, 18 and 22): each robot's possible
// locations in its colour, then the localization result over them: the best solution's
// robots as filled arrows joined by the links used, its rivals dashed, the slides, the truth.
#include "team_render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/grids/error.hpp"
#include "heatmap_layout.hpp"
#include "plot.hpp"
#include "team_marks.hpp"

namespace gridloc::cli {
namespace {

using plot::Box;
using plot::View;
using namespace team_marks;

constexpr int kLeft = 72;                 // room for the y tick labels
constexpr int kRight = 28;                // the right frame clear of the canvas
constexpr int kAxisBelow = 56;            // x tick labels and axis label
constexpr int kMaxPlotWidth = 900;        // the map fitted to at most this many px
constexpr int kMaxPlotHeight = 800;       // both ways
constexpr int kMinPlotWidth = 480;        // a narrow map is shown wider (title, legend)
constexpr int kMinPlotHeight = 200;       // a flat one higher
constexpr double kMarginFraction = 0.05;  // beyond the drawn things, of the longer side

// Colours are BGR.
const cv::Scalar kLinkUnused(150, 150, 150);  // the links not used: dotted grey
const cv::Scalar kOccupied = cv::Scalar::all(layout::kOccupiedGrey);
const cv::Scalar kUnknown = cv::Scalar::all(layout::kUnknownGrey);  // also outside a polygon

/// Robot r's colour: eight well-separated hues, none near the truth's magenta or the map's
/// greys; they cycle beyond eight.
cv::Scalar robot_colour(int r) {
  static const std::array<cv::Scalar, 8> palette{{
      {180, 119, 31},   // blue
      {14, 127, 255},   // orange
      {44, 160, 44},    // green
      {40, 39, 214},    // red
      {189, 103, 148},  // purple
      {75, 86, 140},    // brown
      {34, 189, 188},   // olive
      {207, 190, 23},   // cyan
  }};
  return palette[static_cast<std::size_t>(r) % palette.size()];
}

/// "R1" for robot 0.
std::string robot_label(int r) {
  std::string label = std::to_string(r + 1);
  label.insert(label.begin(), 'R');  // not "R" + ...: GCC 12 warns falsely (-Wrestrict)
  return label;
}

Eigen::Vector2d position(const Pose2& pose) {
  return {pose.x, pose.y};
}

/// Where a candidate's stretch of poses ends (its pose for a single pose).
Eigen::Vector2d end_of(const PoseCandidate& candidate) {
  return position(candidate.pose) + candidate.length * candidate.along;
}

/// Where a solution's robot may slide to (its pose for a fixed solution).
Eigen::Vector2d slide_end(const TeamSolution& solution, int robot) {
  return position(solution.poses[robot]) + solution.slide.length * solution.slide.direction;
}

bool finite(const Pose2& pose) {
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
}

/// "1 pose", "3 poses".
std::string count(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

/// "2 robots (0 to 1)": the robots a link may name.
std::string robot_range(std::size_t n) {
  if (n == 0) return "no robot";
  return count(n, "robot") + (n == 1 ? " (0)" : " (0 to " + std::to_string(n - 1) + ")");
}

/// Throws gridloc::Error when the truth or a solution disagrees with the candidates' robots.
void check_sizes(const TeamPicture& picture) {
  const std::size_t n = picture.candidates.size();
  if (!picture.truth.empty() && picture.truth.size() != n) {
    throw Error("team picture: " + count(picture.truth.size(), "true pose") + " for " +
                count(n, "robot") + " (one per robot, or none)");
  }
  for (std::size_t k = 0; k < picture.solutions.size(); ++k) {
    const std::size_t poses = picture.solutions[k].poses.size();
    if (poses != n) {
      throw Error("team picture: solution " + std::to_string(k) + " has " + count(poses, "pose") +
                  " for " + count(n, "robot"));
    }
  }
}

/// Throws gridloc::Error when a link names a robot that is not there, or links_used a link.
void check_links(const TeamPicture& picture) {
  const std::size_t n = picture.candidates.size();
  for (std::size_t k = 0; k < picture.links.size(); ++k) {
    const VirtualLink& link = picture.links[k];
    for (const int robot : {link.from, link.to}) {
      if (robot < 0 || static_cast<std::size_t>(robot) >= n) {
        throw Error("team picture: link " + std::to_string(k) + " (" + std::to_string(link.from) +
                    "-" + std::to_string(link.to) + ") names robot " + std::to_string(robot) +
                    ", but the picture has " + robot_range(n));
      }
    }
  }
  const std::size_t links = picture.links.size();
  for (const int k : picture.links_used) {
    if (k < 0 || static_cast<std::size_t>(k) >= links) {
      throw Error("team picture: links_used names link " + std::to_string(k) + ", but there are " +
                  count(links, "link"));
    }
  }
}

/// The map's extent: the polygon rings, else the grid's four corners (world frame).
void add_map(Box& box, const TeamPicture& picture) {
  if (picture.polygons) {
    box.add(picture.polygons->boundary);
    return;
  }
  const GridGeometry& g = picture.grid.geometry;
  if (picture.grid.cells.empty()) return;
  const double w = g.width * g.resolution, h = g.height * g.resolution;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(w, 0.0),
                                        Eigen::Vector2d(0.0, h), Eigen::Vector2d(w, h)}) {
    box.add(position(g.to_world_frame({corner.x(), corner.y(), 0.0})));
  }
}

/// What the plot shows: the map, the corners, every candidate, solution and true pose.
Box picture_box(const TeamPicture& picture) {
  Box box;
  add_map(box, picture);
  for (const MapCorner& corner : picture.features.corners) box.add(corner.point);
  for (const std::vector<PoseCandidate>& robot : picture.candidates) {
    for (const PoseCandidate& c : robot) box.add(std::vector{position(c.pose), end_of(c)});
  }
  for (const TeamSolution& s : picture.solutions) {
    for (std::size_t r = 0; r < s.poses.size(); ++r) {
      box.add(std::vector{position(s.poses[r]), slide_end(s, static_cast<int>(r))});
    }
  }
  for (const Pose2& t : picture.truth) box.add(position(t));
  return box;
}

/// The plot area below the title and caption.
struct Layout {
  View view;
  std::vector<std::string> title, caption;
  int width = 0;
};

/// `s` wrapped to `width` px, each '\n' starting a new line.
std::vector<std::string> text_lines(const std::string& s, double scale, int thickness, int width) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find('\n', start), s.size());
    for (std::string& line : plot::wrap(s.substr(start, end - start), scale, thickness, width)) {
      lines.push_back(std::move(line));
    }
    start = end + 1;
  }
  return lines;
}

/// The view fitting the picture into kMaxPlotWidth x kMaxPlotHeight px (grown about its centre
/// to the minimum size), the title and caption wrapped to the image's width above it.
Layout make_layout(const TeamPicture& picture) {
  const Box box = plot::padded(picture_box(picture), kMarginFraction);
  const Eigen::Vector2d size = box.hi - box.lo;
  Layout layout;
  View& view = layout.view;
  view.scale = std::min(kMaxPlotWidth / size.x(), kMaxPlotHeight / size.y());
  const double extra_x = std::max(0.0, kMinPlotWidth / view.scale - size.x()) / 2.0;
  const double extra_y = std::max(0.0, kMinPlotHeight / view.scale - size.y()) / 2.0;
  view.x0 = box.lo.x() - extra_x;
  view.x1 = box.hi.x() + extra_x;
  view.y0 = box.lo.y() - extra_y;
  view.y1 = box.hi.y() + extra_y;
  layout.width = kLeft + view.width() + kRight;
  layout.title = text_lines(picture.title, plot::kTitleScale, 2, layout.width - 24);
  layout.caption = text_lines(picture.caption, plot::kTickScale, 1, layout.width - 24);
  view.origin = {kLeft, plot::title_block_bottom(layout.title.size(), layout.caption.size()) + 24};
  return layout;
}

/// A ring as sub-pixel points; empty when a vertex is not finite.
std::vector<cv::Point> ring_points(const Polygon& ring, const View& view) {
  std::vector<cv::Point> points;
  for (const Eigen::Vector2d& v : ring) {
    if (!v.allFinite()) return {};
    points.push_back(plot::sub(view.px(v.x(), v.y())));
  }
  return points;
}

/// The polygon map: outside and obstacles light grey, free space white, the rings dark.
void paint_polygons(cv::Mat& img, const PolygonMap& map, const View& view) {
  img.setTo(kUnknown);
  plot::Contours rings{ring_points(map.boundary, view)};
  for (const Polygon& obstacle : map.obstacles) rings.push_back(ring_points(obstacle, view));
  plot::fill_rings(img, rings, plot::kWhite);
  plot::outline_rings(img, rings, plot::kInk, 2);
}

/// Each robot's candidates in its colour (seed 003 Figs 13, 17, 20).
void paint_candidates(cv::Mat& img, const TeamPicture& picture, const View& view) {
  for (std::size_t r = 0; r < picture.candidates.size(); ++r) {
    const cv::Scalar colour = robot_colour(static_cast<int>(r));
    for (const PoseCandidate& c : picture.candidates[r]) {
      const Eigen::Vector2d a = position(c.pose), b = end_of(c);
      if (!finite(c.pose) || !b.allFinite()) continue;
      if (c.segment()) {
        placement_mark(img, view.px(a.x(), a.y()), view.px(b.x(), b.y()), c.pose.theta, colour);
      } else {
        candidate_mark(img, view.px(a.x(), a.y()), c.pose.theta, colour);
      }
    }
  }
}

/// Every solution's slides (seed 003's wall pairs), each robot's stretch in its colour.
void paint_slides(cv::Mat& img, const TeamPicture& picture, const View& view) {
  for (const TeamSolution& s : picture.solutions) {
    if (!s.slide.moving()) continue;
    for (std::size_t r = 0; r < s.poses.size(); ++r) {
      const Eigen::Vector2d a = position(s.poses[r]), b = slide_end(s, static_cast<int>(r));
      if (!a.allFinite() || !b.allFinite()) continue;
      double_arrow(img, view.px(a.x(), a.y()), view.px(b.x(), b.y()),
                   robot_colour(static_cast<int>(r)));
    }
  }
}

/// The rival solutions (all but the first), dashed, the lowest ranked first.
void paint_rivals(cv::Mat& img, const TeamPicture& picture, const View& view) {
  for (std::size_t k = picture.solutions.size(); k-- > 1;) {
    const std::vector<Pose2>& poses = picture.solutions[k].poses;
    for (std::size_t r = 0; r < poses.size(); ++r) {
      if (!finite(poses[r])) continue;
      rival_arrow(img, view.px(poses[r].x, poses[r].y), poses[r].theta,
                  robot_colour(static_cast<int>(r)));
    }
  }
}

/// Which links the solution used.
std::vector<bool> used_links(const TeamPicture& picture) {
  std::vector<bool> used(picture.links.size(), false);
  for (const int k : picture.links_used) used[k] = true;
  return used;
}

/// The links between the best solution's robots: the others dotted grey, then those used solid
/// dark over them.
void paint_links(cv::Mat& img, const TeamPicture& picture, const View& view) {
  if (picture.solutions.empty()) return;
  const std::vector<Pose2>& poses = picture.solutions.front().poses;
  const std::vector<bool> used = used_links(picture);
  for (const bool drawing_used : {false, true}) {
    for (std::size_t k = 0; k < picture.links.size(); ++k) {
      const Pose2 &a = poses[picture.links[k].from], &b = poses[picture.links[k].to];
      if (used[k] != drawing_used || !finite(a) || !finite(b)) continue;
      const cv::Point2d pa = view.px(a.x, a.y), pb = view.px(b.x, b.y);
      if (used[k]) {
        plot::line(img, pa, pb, plot::kWhite, 5);
        plot::line(img, pa, pb, plot::kInk, 2);
      } else {
        plot::dashed_line(img, pa, pb, kLinkUnused, 2, 3.0);
      }
    }
  }
}

/// Each used link's length (m) beside its middle.
void label_links(cv::Mat& img, const TeamPicture& picture, const View& view) {
  if (picture.solutions.empty()) return;
  const std::vector<Pose2>& poses = picture.solutions.front().poses;
  for (const int k : picture.links_used) {
    const VirtualLink& link = picture.links[k];
    const Pose2 &a = poses[link.from], &b = poses[link.to];
    if (!finite(a) || !finite(b)) continue;
    const cv::Point2d pa = view.px(a.x, a.y), pb = view.px(b.x, b.y);
    const cv::Point2d d = pb - pa;
    const cv::Point2d normal = cv::Point2d(-d.y, d.x) * (1.0 / std::max(1.0, std::hypot(d.x, d.y)));
    const std::string s = plot::fixed(link.length_m, 2) + " m";
    const cv::Size ts = plot::text_size(s, plot::kTickScale);
    // The label's box clear of the line by 6 px.
    const double clear =
        6.0 + 0.5 * (std::abs(normal.x) * ts.width + std::abs(normal.y) * ts.height);
    const cv::Point2d at = (pa + pb) * 0.5 + normal * clear;
    plot::halo_text(img, s,
                    {static_cast<int>(std::lround(at.x - ts.width / 2.0)),
                     static_cast<int>(std::lround(at.y + ts.height / 2.0))},
                    plot::kTickScale);
  }
}

/// The best solution (seed 003 Figs 14, 18, 22): each robot's arrow, labelled R1, R2, ...
/// beside it, opposite its heading.
void paint_best(cv::Mat& img, const TeamPicture& picture, const View& view) {
  if (picture.solutions.empty()) return;
  const std::vector<Pose2>& poses = picture.solutions.front().poses;
  for (std::size_t r = 0; r < poses.size(); ++r) {
    if (!finite(poses[r])) continue;
    solution_arrow(img, view.px(poses[r].x, poses[r].y), poses[r].theta,
                   robot_colour(static_cast<int>(r)));
  }
  for (std::size_t r = 0; r < poses.size(); ++r) {
    if (!finite(poses[r])) continue;
    const std::string s = robot_label(static_cast<int>(r));
    const cv::Size ts = plot::text_size(s, plot::kLabelScale, 2);
    const cv::Point2d at = view.px(poses[r].x, poses[r].y) - plot::direction(poses[r].theta) * 20.0;
    plot::halo_text(img, s,
                    {static_cast<int>(std::lround(at.x - ts.width / 2.0)),
                     static_cast<int>(std::lround(at.y + ts.height / 2.0))},
                    plot::kLabelScale, robot_colour(static_cast<int>(r)), 2);
  }
}

void paint_truth(cv::Mat& img, const TeamPicture& picture, const View& view) {
  for (const Pose2& t : picture.truth) {
    if (finite(t)) plot::truth_marker(img, view.px(t.x, t.y), t.theta);
  }
}

/// Everything inside the plot area, clipped to it, bottom layer first.
void paint_plot(cv::Mat& img, const TeamPicture& picture, const View& view) {
  cv::Mat area = img(view.rect());
  View local = view;
  local.origin = {0, 0};
  if (picture.polygons) {
    paint_polygons(area, *picture.polygons, local);
  } else {
    plot::paint_grid(area, picture.grid, local);
  }
  for (const MapCorner& c : picture.features.corners) {
    if (c.point.allFinite()) corner_dot(area, local.px(c.point.x(), c.point.y()));
  }
  paint_candidates(area, picture, local);
  paint_links(area, picture, local);
  paint_slides(area, picture, local);
  paint_rivals(area, picture, local);
  paint_truth(area, picture, local);
  paint_best(area, picture, local);
  label_links(area, picture, local);
}

/// The map's swatches: free, walls or occupied, outside or unknown.
void add_map_items(std::vector<plot::LegendItem>& items, const TeamPicture& picture) {
  items.push_back(plot::filled(plot::kWhite, "free space"));
  if (picture.polygons) {
    items.push_back(plot::stroke(plot::kInk, 2, "walls"));
    items.push_back(plot::filled(kUnknown, "outside, obstacles"));
  } else {
    items.push_back(plot::filled(kOccupied, "occupied"));
    items.push_back(plot::filled(kUnknown, "unknown"));
  }
  items.push_back(plot::LegendItem{
      [](cv::Mat& m, const cv::Point2d& p) { corner_dot(m, p + cv::Point2d(8, 0)); },
      "map corner"});
}

/// The marks' items, drawn in ink (on the map they take their robot's colour).
void add_mark_items(std::vector<plot::LegendItem>& items, const TeamPicture& picture) {
  items.push_back(plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) {
                                     candidate_mark(m, p + cv::Point2d(6, 0), 0.0, plot::kInk);
                                   },
                                   "candidate pose (tick: heading)"});
  items.push_back(plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) {
                                     placement_mark(m, p + cv::Point2d(0, 4),
                                                    p + cv::Point2d(26, 4), std::numbers::pi / 2,
                                                    plot::kInk);
                                   },
                                   "wall placement (poses along a wall)"});
  items.push_back(plot::LegendItem{
      [](cv::Mat& m, const cv::Point2d& p) { solution_arrow(m, p, 0.0, plot::kInk); }, "solution"});
  items.push_back(
      plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) { rival_arrow(m, p, 0.0, plot::kInk); },
                       "rival solution"});
  const bool slides = std::any_of(picture.solutions.begin(), picture.solutions.end(),
                                  [](const TeamSolution& s) { return s.slide.moving(); });
  if (slides) {
    items.push_back(plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) {
                                       double_arrow(m, p, p + cv::Point2d(30, 0), plot::kInk);
                                     },
                                     "slide (the solution moves along)"});
  }
}

/// The links' items, the truth's, and one swatch per robot.
void add_link_and_robot_items(std::vector<plot::LegendItem>& items, const TeamPicture& picture) {
  items.push_back(plot::stroke(plot::kInk, 2, "link used (its length)"));
  items.push_back(plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) {
                                     plot::dashed_line(m, p, p + cv::Point2d(26, 0), kLinkUnused, 2,
                                                       3.0);
                                   },
                                   "link not used"});
  if (!picture.truth.empty()) {
    items.push_back(plot::LegendItem{
        [](cv::Mat& m, const cv::Point2d& p) { plot::truth_marker(m, p + cv::Point2d(2, 0), 0.0); },
        "truth"});
  }
  for (std::size_t r = 0; r < picture.candidates.size(); ++r) {
    items.push_back(
        plot::filled(robot_colour(static_cast<int>(r)), robot_label(static_cast<int>(r))));
  }
}

std::vector<plot::LegendItem> team_legend(const TeamPicture& picture) {
  std::vector<plot::LegendItem> items;
  add_map_items(items, picture);
  add_mark_items(items, picture);
  add_link_and_robot_items(items, picture);
  return items;
}

}  // namespace

cv::Mat render_team(const TeamPicture& picture) {
  check_sizes(picture);
  check_links(picture);
  const Layout layout = make_layout(picture);
  const std::vector<plot::LegendItem> items = team_legend(picture);
  const int plot_bottom = layout.view.rect().br().y;
  const int legend_room = 28 * static_cast<int>(items.size()) + 40;  // one item a row at most
  cv::Mat img(plot_bottom + kAxisBelow + legend_room, layout.width, CV_8UC3, plot::kWhite);
  paint_plot(img, picture, layout.view);
  plot::scale_bar(img, layout.view);
  plot::axes_m(img, layout.view, 0.0, 0.0, "x (m)", "y (m)");
  plot::title_block(img, layout.title, layout.caption);
  const int last = plot::legend(img, items, 12, plot_bottom + kAxisBelow + 20, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
