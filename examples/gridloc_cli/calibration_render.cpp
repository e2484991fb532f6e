// The calibration plot (calibration_render.hpp).
#include "calibration_render.hpp"

#include <cmath>

#include "gridloc/grids/error.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

constexpr int kPlotSide = 440;  ///< px of the unit square
constexpr int kLeft = 90;       ///< px left of the plot (the axis labels)

/// BGR: blue, orange, green, red, purple, brown (then again).
const cv::Scalar kPalette[] = {{180, 119, 31}, {14, 127, 255},  {44, 160, 44},
                               {40, 39, 214},  {189, 103, 148}, {75, 86, 140}};

void draw_curve(cv::Mat& img, const plot::View& view, const std::vector<double>& levels,
                const std::vector<double>& observed, const cv::Scalar& colour) {
  bool have_last = false;
  cv::Point2d last;
  for (std::size_t k = 0; k < levels.size() && k < observed.size(); ++k) {
    if (!std::isfinite(observed[k])) continue;
    const cv::Point2d p = view.px(levels[k], observed[k]);
    if (have_last) plot::line(img, last, p, colour, 2);
    plot::circle(img, p, 3.0, colour, -1);
    last = p;
    have_last = true;
  }
}

}  // namespace

void write_calibration_plot(const std::string& path, const std::string& title,
                            const std::string& caption, const std::vector<double>& levels,
                            const std::vector<CoverageCurve>& curves) {
  if (curves.empty()) throw Error("calibration plot: no curve to draw");
  const int top = plot::title_block_bottom(1, 1) + 16;
  plot::View view;  // the unit square: expected (x) against observed (y)
  view.scale = kPlotSide;
  view.origin = {kLeft, top};
  cv::Mat img(top + kPlotSide + 90 + 28 * static_cast<int>(curves.size()), kLeft + kPlotSide + 150,
              CV_8UC3, plot::kWhite);
  plot::title_block(img, {title}, {caption});
  for (int k = 1; k < 10; ++k) {  // light grid every 0.1
    const double v = 0.1 * k;
    plot::line(img, view.px(v, 0.0), view.px(v, 1.0), plot::kGridLine, 1);
    plot::line(img, view.px(0.0, v), view.px(1.0, v), plot::kGridLine, 1);
  }
  plot::dashed_line(img, view.px(0.0, 0.0), view.px(1.0, 1.0), plot::kInk, 1);
  std::vector<plot::LegendItem> items = {{[](cv::Mat& canvas, const cv::Point2d& p) {
                                            plot::dashed_line(canvas, p, p + cv::Point2d(26, 0),
                                                              plot::kInk, 1);
                                          },
                                          "calibrated"}};
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const cv::Scalar& colour = kPalette[c % std::size(kPalette)];
    draw_curve(img, view, levels, curves[c].observed, colour);
    items.push_back(plot::stroke(colour, 2, curves[c].label));
  }
  plot::axes_m(img, view, 0.0, 0.0, "expected: the ellipse's probability p",
               "observed: errors within it");
  const int last = plot::legend(img, items, 12, top + kPlotSide + 70, img.cols - 8);
  plot::write_png(path, img.rowRange(0, std::min(img.rows, last + 16)).clone());
}

}  // namespace gridloc::cli
