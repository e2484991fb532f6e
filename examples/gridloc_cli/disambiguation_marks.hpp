#pragma once
// The colours and marks of `gridloc disambiguate`'s picture (disambiguation_render.cpp): the
// overlay's regions and edges, the hypotheses' colours, the random points, the path's stops,
// the start, the lower bound's point and an eliminated hypothesis. Sizes in px.
#include <opencv2/core.hpp>

namespace gridloc::cli::disambiguation_marks {

// Colours are BGR.
inline const cv::Scalar kOiFill(245, 222, 185);      // OI: light blue
inline const cv::Scalar kUsefulFill(140, 225, 140);  // U: light green, blended
inline const cv::Scalar kUsefulEdge(50, 140, 50);    // U's outline
inline constexpr double kUsefulAlpha = 0.55;         // U's opacity
inline const cv::Scalar kInternalEdge(0, 140, 255);  // OI's internal edges: orange
inline const cv::Scalar kSilhouette(45, 45, 45);     // OI's silhouette edges, the walls
inline const cv::Scalar kSample(125, 125, 125);      // random points: grey
inline const cv::Scalar kPath(30, 30, 150);          // the path in the start frame: dark red
inline const cv::Scalar kBound(170, 40, 120);        // the lower bound's point: purple
inline const cv::Scalar kOutside(205, 205, 205);     // outside the map, obstacles
inline constexpr double kFaded = 0.4;                // opacity of an eliminated hypothesis

/// Hypothesis i's colour: ten dark, distinct hues, none near OI's orange edges, U's green,
/// the path's dark red or the truth's magenta; they cycle beyond ten.
cv::Scalar hypothesis_colour(int i);

/// A random point: a small grey dot.
void sample_dot(cv::Mat& img, const cv::Point2d& p);

/// Stop `n`: a white disc with a dark red rim, its number to the upper right.
void stop_marker(cv::Mat& img, const cv::Point2d& p, int n);

/// The start (the overlay's origin): a black square with a white rim.
void start_marker(cv::Mat& img, const cv::Point2d& p);

/// The lower bound's nearest informative point: a small purple star.
void bound_marker(cv::Mat& img, const cv::Point2d& p);

/// Hypothesis n drawn faded: blended with what lies under it.
void faded_marker(cv::Mat& img, const cv::Point2d& p, double heading, int n);

}  // namespace gridloc::cli::disambiguation_marks
