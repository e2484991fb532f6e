// The relations picture: the worst pairs, both scans at the truth and at the answer.
#include "relations_render.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "gridloc/grids/error.hpp"
#include "plot.hpp"

namespace gridloc::cli {
namespace {

using plot::Box;
using plot::View;

constexpr int kColumns = 3;
constexpr int kPlot = 400;                ///< a panel's plot area (px, square)
constexpr int kPanelWidth = 440;          ///< a panel with its margins
constexpr int kPanelHeader = 64;          ///< the panel's text lines above its plot
constexpr double kReachM = 15.0;          ///< a panel shows at most this far from the reference
const cv::Scalar kReference(90, 90, 90);  // dark grey
const cv::Scalar kAtTruth(60, 160, 40);   // green
const cv::Scalar kAtAnswer(40, 40, 210);  // red
const cv::Scalar kEllipse(200, 120, 30);  // blue

double error_key(const RelationTrial& t) {
  return t.translation_error_m + 0.01 * t.rotation_error_deg;
}

std::vector<Eigen::Vector2d> moved(const std::vector<Eigen::Vector2d>& points, const Pose2& pose) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    out.emplace_back(pose.x + c * p.x() - s * p.y(), pose.y + s * p.x() + c * p.y());
  }
  return out;
}

/// The square view of the panel's points within kReachM of the reference robot.
View panel_view(const std::vector<const std::vector<Eigen::Vector2d>*>& clouds, cv::Point origin) {
  Box box;
  box.add(Eigen::Vector2d::Zero());
  for (const auto* cloud : clouds) {
    for (const Eigen::Vector2d& p : *cloud) {
      if (p.norm() <= kReachM) box.add(p);
    }
  }
  box = plot::padded(box, 0.04);
  const Eigen::Vector2d centre = 0.5 * (box.lo + box.hi);
  const double half = 0.5 * std::max(box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y());
  View view;
  view.x0 = centre.x() - half, view.x1 = centre.x() + half;
  view.y0 = centre.y() - half, view.y1 = centre.y() + half;
  view.scale = kPlot / (2.0 * half);
  view.origin = origin;
  return view;
}

void dots(cv::Mat& img, const View& view, const std::vector<Eigen::Vector2d>& points,
          const cv::Scalar& colour) {
  for (const Eigen::Vector2d& p : points) {
    const cv::Point2d px = view.px(p.x(), p.y());
    if (view.rect().contains(cv::Point(px))) plot::circle(img, px, 1.6, colour, -1);
  }
}

/// The 2-sigma ellipse of the covariance's x, y block about `pose`.
void two_sigma_ellipse(cv::Mat& img, const View& view, const Pose2& pose,
                       const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(covariance.topLeftCorner<2, 2>());
  const Eigen::Vector2d sigma = axes.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  // Nothing to draw for a zero or undefined covariance; an ellipse far wider than the panel
  // is drawn at 4 panels wide (its pixel size must fit an int).
  if (!(sigma(1) > 0.0) || !std::isfinite(sigma(1))) return;
  const auto px = [&](double metres) {
    return static_cast<int>(std::min(2.0 * metres * view.scale, 4.0 * kPlot) * (1 << plot::kShift));
  };
  const Eigen::Vector2d major = axes.eigenvectors().col(1);
  const double angle_deg = -std::atan2(major.y(), major.x()) * 180.0 / std::numbers::pi;
  const cv::Point2d centre = view.px(pose.x, pose.y);
  cv::ellipse(img, plot::sub(centre), cv::Size(px(sigma(1)), px(sigma(0))), angle_deg, 0.0, 360.0,
              kEllipse, 2, cv::LINE_AA, plot::kShift);
}

/// The panel's text lines: the pair and its errors; its verdict and motion; its overlaps.
std::vector<std::string> panel_text(const RelationTrial& t) {
  std::string verdict = t.verdict ? to_string(*t.verdict) : "no verdict (icp)";
  if (!std::isnan(t.confidence)) verdict += " (" + plot::fixed(t.confidence, 2) + ")";
  return {"pair " + std::to_string(t.pair) + ": " + plot::fixed(t.translation_error_m, 3) + " m, " +
              plot::fixed(t.rotation_error_deg, 1) + " deg off" + (t.failed ? " - FAILED" : ""),
          verdict + "; moved " + plot::fixed(t.motion_m, 2) + " m, " +
              plot::fixed(t.motion_deg, 0) + " deg",
          "overlap " + plot::fixed(t.overlap, 2) + " at the relation, " +
              plot::fixed(t.answer_overlap, 2) + " at the answer"};
}

void draw_panel(cv::Mat& img, const RelationPanel& panel, cv::Point corner) {
  const RelationTrial& t = panel.trial;
  const auto at_truth = moved(panel.current, t.truth);
  const auto at_answer = moved(panel.current, t.answer);
  const View view =
      panel_view({&panel.reference, &at_truth, &at_answer}, corner + cv::Point(20, kPanelHeader));
  cv::rectangle(img, view.rect(), plot::kSwatchEdge, 1);
  dots(img, view, panel.reference, kReference);
  dots(img, view, at_truth, kAtTruth);
  dots(img, view, at_answer, kAtAnswer);
  two_sigma_ellipse(img, view, t.answer, t.covariance);
  plot::hypothesis_marker(img, view.px(0.0, 0.0), 0.0, 0);
  plot::truth_marker(img, view.px(t.truth.x, t.truth.y), t.truth.theta);
  plot::estimate_marker(img, view.px(t.answer.x, t.answer.y), t.answer.theta);
  plot::scale_bar(img, view);
  int baseline = corner.y + 18;
  for (const std::string& line : panel_text(t)) {
    plot::text(img, line, {corner.x + 20, baseline}, plot::kTickScale,
               t.failed ? kAtAnswer : plot::kInk);
    baseline += 18;
  }
}

std::vector<plot::LegendItem> legend_items() {
  const auto dot = [](const cv::Scalar& colour) {
    return [colour](cv::Mat& img, const cv::Point2d& p) {
      for (int k = 0; k < 4; ++k) plot::circle(img, p + cv::Point2d(4 + 6 * k, 0), 1.8, colour, -1);
    };
  };
  return {{dot(kReference), "reference scan (its robot: the disc 0)"},
          {dot(kAtTruth), "current scan at the relation's motion"},
          {dot(kAtAnswer), "current scan at the answer"},
          {[](cv::Mat& img, const cv::Point2d& p) {
             plot::truth_marker(img, p + cv::Point2d(12, 0), 0.0);
           },
           "the relation"},
          {[](cv::Mat& img, const cv::Point2d& p) {
             plot::estimate_marker(img, p + cv::Point2d(12, 0), 0.0);
           },
           "the answer"},
          plot::stroke(kEllipse, 2, "its 2-sigma ellipse")};
}

}  // namespace

std::vector<std::size_t> worst_trials(const std::vector<RelationTrial>& trials, std::size_t count) {
  std::vector<std::size_t> order(trials.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (trials[a].failed != trials[b].failed) return trials[a].failed;
    return error_key(trials[a]) > error_key(trials[b]);
  });
  order.resize(std::min(count, order.size()));
  return order;
}

cv::Mat render_relations(const RelationsPicture& picture) {
  if (picture.panels.empty()) throw Error("relations plot: no pair to draw");
  const int rows = (static_cast<int>(picture.panels.size()) + kColumns - 1) / kColumns;
  const int top = plot::title_block_bottom(1, 1) + 12;
  const int panel_height = kPanelHeader + kPlot + 24;
  const std::vector<plot::LegendItem> items = legend_items();
  cv::Mat img(top + rows * panel_height + 40 + 28 * static_cast<int>(items.size()),
              kColumns * kPanelWidth, CV_8UC3, plot::kWhite);
  plot::title_block(img, {picture.title}, {picture.caption});
  for (std::size_t k = 0; k < picture.panels.size(); ++k) {
    const cv::Point corner(static_cast<int>(k % kColumns) * kPanelWidth,
                           top + static_cast<int>(k / kColumns) * panel_height);
    draw_panel(img, picture.panels[k], corner);
  }
  const int last = plot::legend(img, items, 12, top + rows * panel_height + 24, img.cols - 8);
  return img.rowRange(0, std::min(img.rows, last + 16)).clone();
}

}  // namespace gridloc::cli
