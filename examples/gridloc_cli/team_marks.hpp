#pragma once
// The marks `gridloc team`'s image is drawn with (team_render.cpp): corner dots, candidates'
// heading ticks and wall placements, the best solution's arrows, its rivals' dashed ones and
// the slides' double arrows, each on a white halo. Sizes in px.
#include <opencv2/core.hpp>

namespace gridloc::cli::team_marks {

constexpr double kTick = 11.0;   // a candidate's heading tick (px)
constexpr double kArrow = 26.0;  // a solution's heading arrow (px)
constexpr double kHead = 8.0;    // arrow heads (px)

/// A map corner: a small grey dot.
void corner_dot(cv::Mat& img, const cv::Point2d& p);

/// A heading tick from `p` (px) outwards, starting `from` px off it, on a white halo.
void heading_tick(cv::Mat& img, const cv::Point2d& p, double heading, double from,
                  const cv::Scalar& colour);

/// A single-pose candidate: a small ring with its heading tick.
void candidate_mark(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour);

/// A wall placement: the stretch of positions from a to b, heading ticks at both ends.
void placement_mark(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b, double heading,
                    const cv::Scalar& colour);

/// The two strokes of an arrow head at `tip` pointing along unit `u` (px).
void arrow_head(cv::Mat& img, const cv::Point2d& tip, const cv::Point2d& u,
                const cv::Scalar& colour, int thickness);

/// A slide's stretch: a double-headed arrow from a to b (px).
void double_arrow(cv::Mat& img, const cv::Point2d& a, const cv::Point2d& b,
                  const cv::Scalar& colour);

/// The best solution's robot: a filled disc with a heading arrow on a white halo.
void solution_arrow(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour);

/// A circle drawn as eight dashes.
void dashed_circle(cv::Mat& img, const cv::Point2d& c, double radius, const cv::Scalar& colour,
                   int thickness);

/// A rival solution's robot: the arrow's outline, dashed.
void rival_arrow(cv::Mat& img, const cv::Point2d& p, double heading, const cv::Scalar& colour);

}  // namespace gridloc::cli::team_marks
