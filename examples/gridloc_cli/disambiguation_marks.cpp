// The colours and marks of `gridloc disambiguate`'s picture (disambiguation_marks.hpp).
#include "disambiguation_marks.hpp"

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "plot.hpp"

namespace gridloc::cli::disambiguation_marks {

/// Hypothesis i's colour: ten dark, distinct hues, none near OI's orange edges, U's green,
/// the path's dark red or the truth's magenta; they cycle beyond ten.
cv::Scalar hypothesis_colour(int i) {
  static const std::vector<cv::Scalar> palette{
      {200, 90, 20},   // blue
      {150, 40, 130},  // purple
      {130, 140, 0},   // teal
      {0, 125, 125},   // olive
      {30, 75, 140},   // brown
      {225, 150, 50},  // sky blue
      {110, 30, 30},   // navy
      {0, 150, 195},   // dark gold
      {150, 120, 95},  // slate
      {70, 110, 0},    // dark green
  };
  return palette[static_cast<std::size_t>(i) % palette.size()];
}

void sample_dot(cv::Mat& img, const cv::Point2d& p) {
  plot::circle(img, p, 2.2, kSample, cv::FILLED);
}

/// Stop `n`: a white disc with a dark red rim, its number to the upper right.
void stop_marker(cv::Mat& img, const cv::Point2d& p, int n) {
  plot::circle(img, p, 6.0, plot::kWhite, cv::FILLED);
  plot::circle(img, p, 6.0, kPath, 2);
  if (n > 0) {
    plot::halo_text(
        img, std::to_string(n),
        {static_cast<int>(std::lround(p.x)) + 8, static_cast<int>(std::lround(p.y)) - 7},
        plot::kTickScale, kPath, 1);
  }
}

/// The start (the overlay's origin): a black square with a white rim.
void start_marker(cv::Mat& img, const cv::Point2d& p) {
  const cv::Point c(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  cv::rectangle(img, c - cv::Point(7, 7), c + cv::Point(7, 7), plot::kWhite, cv::FILLED);
  cv::rectangle(img, c - cv::Point(5, 5), c + cv::Point(5, 5), plot::kInk, cv::FILLED);
}

/// The lower bound's nearest informative point: a small purple star.
void bound_marker(cv::Mat& img, const cv::Point2d& p) {
  for (const auto& [colour, thickness] : {std::pair{plot::kWhite, 5}, std::pair{kBound, 2}}) {
    for (int k = 0; k < 3; ++k) {
      const double a = k * std::numbers::pi / 3.0 + std::numbers::pi / 2.0;
      const cv::Point2d d(7.0 * std::cos(a), 7.0 * std::sin(a));
      plot::line(img, p - d, p + d, colour, thickness);
    }
  }
}

/// Hypothesis n drawn faded: blended with what lies under it.
void faded_marker(cv::Mat& img, const cv::Point2d& p, double heading, int n) {
  const cv::Rect box = cv::Rect(static_cast<int>(p.x) - 40, static_cast<int>(p.y) - 40, 80, 80) &
                       cv::Rect(0, 0, img.cols, img.rows);
  if (box.empty()) return;
  cv::Mat under = img(box);
  cv::Mat layer = under.clone();
  plot::hypothesis_marker(layer, p - cv::Point2d(box.tl()), heading, n);
  cv::addWeighted(layer, kFaded, under, 1.0 - kFaded, 0.0, under);
}

}  // namespace gridloc::cli::disambiguation_marks
