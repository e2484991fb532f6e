// The marks of `gridloc team`'s image (team_marks.hpp).
#include "team_marks.hpp"

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "plot.hpp"

namespace gridloc::cli::team_marks {
namespace {

const cv::Scalar kCorner(150, 150, 150);  // map corners

}  // namespace

void corner_dot(cv::Mat& img, const cv::Point2d& p) {
  plot::circle(img, p, 2.0, kCorner, cv::FILLED);
}

/// A heading tick from `p` (px) outwards, starting `from` px off it, on a white halo.
void heading_tick(cv::Mat& img, const cv::Point2d& p, double heading, double from,
                  const cv::Scalar& colour) {
  const cv::Point2d d = plot::direction(heading);
  plot::line(img, p + d * from, p + d * (from + kTick), plot::kWhite, 5);
  plot::line(img, p + d * from, p + d * (from + kTick), colour, 2);
}

/// A single-pose candidate: a small ring with its heading tick.
void candidate_mark(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour) {
  heading_tick(img, p, heading, 4.5, colour);
  plot::circle(img, p, 4.5, plot::kWhite, 4);
  plot::circle(img, p, 4.5, colour, 2);
}

/// A wall placement: the stretch of positions from a to b, heading ticks at both ends.
void placement_mark(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, double heading,
                    const cv::Scalar& colour) {
  plot::line(img, a, b, plot::kWhite, 7);
  heading_tick(img, a, heading, 0.0, colour);
  heading_tick(img, b, heading, 0.0, colour);
  plot::line(img, a, b, colour, 3);
}

/// The two strokes of an arrow head at `tip` pointing along unit `u` (px).
void arrow_head(cv::Mat& img, const cv::Point2d& tip, const cv::Point2d& u,
                const cv::Scalar& colour, int thickness) {
  const double a = 5.0 * std::numbers::pi / 6.0;  // 150 deg back from the tip
  for (const double turn : {a, -a}) {
    const cv::Point2d w(u.x * std::cos(turn) - u.y * std::sin(turn),
                        u.x * std::sin(turn) + u.y * std::cos(turn));
    plot::line(img, tip, tip + w * kHead, colour, thickness);
  }
}

/// A slide's stretch: a double-headed arrow from a to b (px).
void double_arrow(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b,
                  const cv::Scalar& colour) {
  const cv::Point2d d = b - a;
  const double length = std::hypot(d.x, d.y);
  if (!(length >= 1.0)) return;
  const cv::Point2d u = d / length;
  for (const auto& [c, thickness] : {std::pair{plot::kWhite, 5}, std::pair{colour, 2}}) {
    plot::line(img, a, b, c, thickness);
    arrow_head(img, b, u, c, thickness);
    arrow_head(img, a, -u, c, thickness);
  }
}

/// The best solution's robot: a filled disc with a heading arrow on a white halo.
void solution_arrow(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour) {
  const cv::Point2d d = plot::direction(heading);
  const cv::Point2d tip = p + d * kArrow;
  for (const auto& [c, thickness] : {std::pair{plot::kWhite, 6}, std::pair{colour, 3}}) {
    plot::line(img, p, tip, c, thickness);
    arrow_head(img, tip, d, c, thickness);
  }
  plot::circle(img, p, 8.0, plot::kWhite, cv::FILLED);
  plot::circle(img, p, 6.0, colour, cv::FILLED);
}

/// A circle drawn as eight dashes.
void dashed_circle(cv::Mat& img, const cv::Point2d& c, double radius, const cv::Scalar& colour,
                   int thickness) {
  const int r = static_cast<int>(std::lround(radius * (1 << plot::kShift)));
  for (int k = 0; k < 8; ++k) {
    cv::ellipse(img, plot::sub(c), {r, r}, 0.0, 45.0 * k, 45.0 * k + 25.0, colour, thickness,
                cv::LINE_AA, plot::kShift);
  }
}

/// A rival solution's robot: the arrow's outline, dashed.
void rival_arrow(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour) {
  const cv::Point2d d = plot::direction(heading);
  const cv::Point2d tip = p + d * kArrow;
  dashed_circle(img, p, 8.0, colour, 2);
  plot::dashed_line(img, p + d * 8.0, tip, colour, 2, 4.0);
  arrow_head(img, tip, d, colour, 2);
}

}  // namespace gridloc::cli::team_marks
