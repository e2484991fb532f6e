// The track picture: the map and the track by verdict, the weights over the updates.
#include "track_render.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "gridloc/grids/error.hpp"
#include "heatmap_layout.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using plot::Box;
using plot::View;

constexpr int kLeft = 72, kRight = 24, kAxisBelow = 56;
constexpr double kMaxPlotWidth = 1100.0, kMaxPlotHeight = 900.0;
constexpr int kStripHeight = 160;  ///< the weights' strip

const cv::Scalar kLocalized(60, 160, 40);     // green
const cv::Scalar kAmbiguous(0, 150, 240);     // orange
const cv::Scalar kNotLocalized(40, 40, 210);  // red
const cv::Scalar kSearch(200, 120, 30);       // blue
const cv::Scalar kSecond(150, 150, 150);      // the second place's weight
const cv::Scalar kSearchShade(245, 228, 210);

cv::Scalar verdict_colour(Verdict verdict) {
  return verdict == Verdict::Localized   ? kLocalized
         : verdict == Verdict::Ambiguous ? kAmbiguous
                                         : kNotLocalized;
}

/// The track's and the truth's extent, padded.
Box track_box(const TrackPicture& picture) {
  Box box;
  for (const TrackStep& step : picture.steps) {
    box.add(Eigen::Vector2d(step.estimate.pose.x, step.estimate.pose.y));
  }
  for (const Pose2& t : picture.truth) box.add(Eigen::Vector2d(t.x, t.y));
  return plot::padded(box, 0.06);
}

View make_view(const TrackPicture& picture, int top) {
  const Box box = track_box(picture);
  const Eigen::Vector2d size = box.hi - box.lo;
  View view;
  view.scale = std::min(kMaxPlotWidth / size.x(), kMaxPlotHeight / size.y());
  view.x0 = box.lo.x();
  view.x1 = box.hi.x();
  view.y0 = box.lo.y();
  view.y1 = box.hi.y();
  view.origin = {kLeft, top};
  return view;
}

/// A rejected jump: a black X.
void cross(cv::Mat& img, const cv::Point2d& p) {
  plot::line(img, p + cv::Point2d(-5, -5), p + cv::Point2d(5, 5), plot::kInk, 2);
  plot::line(img, p + cv::Point2d(-5, 5), p + cv::Point2d(5, -5), plot::kInk, 2);
}

/// The map, the truth, the track's dots by verdict, the searches' rings and the jumps' X.
void paint_map(cv::Mat& img, const TrackPicture& picture, const View& view) {
  cv::Mat area = img(view.rect());
  View local = view;
  local.origin = {0, 0};
  plot::paint_grid(area, picture.map, local);
  for (std::size_t k = 1; k < picture.truth.size(); ++k) {
    const Pose2 &a = picture.truth[k - 1], &b = picture.truth[k];
    plot::line(area, local.px(a.x, a.y), local.px(b.x, b.y), plot::kTruth, 1);
  }
  for (const TrackStep& step : picture.steps) {
    const cv::Point2d p = local.px(step.estimate.pose.x, step.estimate.pose.y);
    plot::circle(area, p, 2.5, verdict_colour(step.estimate.verdict), cv::FILLED);
    if (step.status.search_finished) plot::circle(area, p, 7.0, kSearch, 2);
    if (step.status.jump_rejected) cross(area, p);
  }
}

/// The weights' strip: per update the heaviest place's weight and the second's, the updates
/// with a search under way shaded, a dot per update in its verdict's colour along the top.
void paint_weights(cv::Mat& img, const TrackPicture& picture, const cv::Rect& strip) {
  const std::size_t n = picture.steps.size();
  const auto x_of = [&](std::size_t k) {
    return strip.x + (n > 1 ? strip.width * double(k) / double(n - 1) : 0.0);
  };
  const auto y_of = [&](double w) { return strip.y + strip.height * (1.0 - w); };
  for (std::size_t k = 0; k < n; ++k) {
    if (picture.steps[k].status.search_slices == 0) continue;
    cv::rectangle(img, cv::Point(int(x_of(k)) - 1, strip.y),
                  cv::Point(int(x_of(k)) + 1, strip.y + strip.height), kSearchShade, cv::FILLED);
  }
  cv::rectangle(img, strip, plot::kInk, 1);
  for (std::size_t k = 1; k < n; ++k) {
    const auto weight = [&](std::size_t i, std::size_t rank) {
      const std::vector<Hypothesis>& a = picture.steps[i].estimate.alternatives;
      return rank < a.size() && !std::isnan(a[rank].weight) ? a[rank].weight : 0.0;
    };
    plot::line(img, {x_of(k - 1), y_of(weight(k - 1, 1))}, {x_of(k), y_of(weight(k, 1))}, kSecond,
               1);
    plot::line(img, {x_of(k - 1), y_of(weight(k - 1, 0))}, {x_of(k), y_of(weight(k, 0))},
               plot::kInk, 1);
  }
  for (std::size_t k = 0; k < n; ++k) {
    plot::circle(img, {x_of(k), double(strip.y) - 5.0}, 1.5,
                 verdict_colour(picture.steps[k].estimate.verdict), cv::FILLED);
  }
  plot::text(img, "1", {strip.x - 14, strip.y + 5}, plot::kTickScale);
  plot::text(img, "0", {strip.x - 14, strip.y + strip.height + 4}, plot::kTickScale);
  plot::text(img, "weight of the heaviest place (black) and the second (grey), update by update",
             {strip.x, strip.y + strip.height + 18}, plot::kTickScale);
}

std::vector<plot::LegendItem> legend_items(const TrackPicture& picture) {
  std::vector<plot::LegendItem> items = {plot::filled(kLocalized, "localized"),
                                         plot::filled(kAmbiguous, "ambiguous"),
                                         plot::filled(kNotLocalized, "not localized")};
  if (!picture.truth.empty()) items.push_back(plot::stroke(plot::kTruth, 2, "truth"));
  items.push_back(plot::LegendItem{[](cv::Mat& m, const cv::Point2d& p) {
                                     plot::circle(m, p + cv::Point2d(8, 0), 7.0, kSearch, 2);
                                   },
                                   "a search finished: its places joined"});
  items.push_back(plot::LegendItem{
      [](cv::Mat& m, const cv::Point2d& p) { cross(m, p + cv::Point2d(8, 0)); }, "jump rejected"});
  items.push_back(plot::filled(kSearchShade, "search under way (strip)"));
  return items;
}

}  // namespace

cv::Mat render_track(const TrackPicture& picture) {
  if (!picture.truth.empty() && picture.truth.size() != picture.steps.size()) {
    throw Error("track plot: the truth must have one pose per step");
  }
  if (picture.steps.empty()) throw Error("track plot: no step to draw");
  const std::vector<std::string> title = {picture.title};
  const std::vector<std::string> caption = {picture.caption};
  const View view = make_view(picture, plot::title_block_bottom(1, 1) + 24);
  const int width = std::max(kLeft + view.width() + kRight, 760);
  const cv::Rect strip(kLeft, view.rect().br().y + kAxisBelow + 20, width - kLeft - kRight,
                       kStripHeight);
  const std::vector<plot::LegendItem> items = legend_items(picture);
  cv::Mat img(strip.br().y + 40 + 28 * int(items.size()), width, CV_8UC3, plot::kWhite);
  paint_map(img, picture, view);
  plot::scale_bar(img, view);
  plot::axes_m(img, view, 0.0, 0.0, "x (m)", "y (m)");
  paint_weights(img, picture, strip);
  plot::title_block(img, title, caption);
  const int last = plot::legend(img, items, 12, strip.br().y + 40, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
