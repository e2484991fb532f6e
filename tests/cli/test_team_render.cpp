// The picture of `gridloc team` (examples/gridloc_cli/team_render.cpp): two robots on seed
// 003's T-shaped map (ch. V A), their candidates, the best solution and a sliding rival.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <string>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "team_render.hpp"

namespace gridloc::cli {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The palette's first two colours (BGR): R1 blue, R2 orange.
const cv::Vec3b kRobot1(180, 119, 31);
const cv::Vec3b kRobot2(14, 127, 255);
// Rows at the bottom the legend takes at most for this picture (its items wrap in ~4 rows).
constexpr int kLegendRows = 200;

/// Seed 003's T: a 3 m x 1 m bar on top of a 1 m x 2 m stem.
PolygonMap t_map() {
  return make_polygon_map({{1, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 3}, {0, 3}, {0, 2}, {1, 2}}, {});
}

/// Ch. V A: robot 1 at (1.2, 1.2) heading 30 deg, robot 2 at (0.3, 2.5) heading 75 deg; robot 1
/// has two corner placements, robot 2 a wall placement and one corner placement; the best
/// solution is the truth, its mirror image a rival that slides.
TeamPicture two_robot_picture() {
  TeamPicture picture;
  picture.title = "T-shaped map: two robots";
  picture.caption = "2 solutions, ambiguous";
  picture.polygons = t_map();
  for (const Eigen::Vector2d& v : picture.polygons->boundary) {
    MapCorner corner;
    corner.point = v;
    picture.features.corners.push_back(corner);
  }
  const Pose2 truth1{1.2, 1.2, 30 * kDeg}, truth2{0.3, 2.5, 75 * kDeg};
  const Pose2 mirror1{1.8, 1.2, 150 * kDeg}, mirror2{2.7, 2.5, 105 * kDeg};
  PoseCandidate wall;
  wall.pose = {0.3, 2.2, 75 * kDeg};
  wall.along = Eigen::Vector2d::UnitY();
  wall.length = 0.6;
  picture.candidates = {{{truth1}, {mirror1}}, {wall, {mirror2}}};
  TeamSolution best, rival;
  best.poses = {truth1, truth2};
  best.candidates = {0, 0};
  rival.poses = {mirror1, mirror2};
  rival.candidates = {1, 1};
  rival.slide.direction = Eigen::Vector2d::UnitY();
  rival.slide.length = 0.3;
  picture.solutions = {best, rival};
  const double length = std::hypot(truth2.x - truth1.x, truth2.y - truth1.y);
  picture.links = {{0, 1, length, 0.0, 0.0}, {1, 0, length, 0.0, 0.0}};
  picture.links_used = {0};
  picture.truth = {truth1, truth2};
  return picture;
}

/// Pixels of exactly `colour` in rows [0, rows).
int count_colour(const cv::Mat& img, int rows, const cv::Vec3b& colour) {
  int n = 0;
  for (int r = 0; r < std::min(rows, img.rows); ++r) {
    for (int c = 0; c < img.cols; ++c) n += img.at<cv::Vec3b>(r, c) == colour;
  }
  return n;
}

/// Pixels that are not white in rows [first, img.rows).
int count_ink(const cv::Mat& img, int first) {
  int n = 0;
  for (int r = std::max(0, first); r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) n += img.at<cv::Vec3b>(r, c) != cv::Vec3b(255, 255, 255);
  }
  return n;
}

/// The message of the gridloc::Error render_team throws (empty when it throws none).
std::string render_error(const TeamPicture& picture) {
  try {
    render_team(picture);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(TeamRender, TwoRobotsOnTheTMapDrawEachRobotInItsColourAndTheLegend) {
  const cv::Mat img = render_team(two_robot_picture());
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.type(), CV_8UC3);
  EXPECT_GE(img.cols, 500);
  EXPECT_LE(img.cols, 1000);  // the map fitted to at most 900 px, the axes beside it
  EXPECT_GE(img.rows, 500);
  EXPECT_LE(img.rows, 1400);
  // Both robots' marks above the legend (the legend's swatches alone would not count).
  EXPECT_GT(count_colour(img, img.rows - kLegendRows, kRobot1), 100);
  EXPECT_GT(count_colour(img, img.rows - kLegendRows, kRobot2), 100);
  // The legend's last row of text in the bottom strip.
  EXPECT_GT(count_ink(img, img.rows - 30), 100);
}

TEST(TeamRender, AnOccupancyMapShowsItsOccupiedCellsDarkGrey) {
  TeamPicture picture = two_robot_picture();
  picture.grid = rasterize_polygon_map(*picture.polygons, 0.05);
  picture.polygons.reset();
  const cv::Mat img = render_team(picture);
  ASSERT_FALSE(img.empty());
  EXPECT_GT(count_colour(img, img.rows - kLegendRows, cv::Vec3b(60, 60, 60)), 1000);
  EXPECT_GT(count_colour(img, img.rows - kLegendRows, kRobot1), 100);
}

TEST(TeamRender, TheTruthMustGiveOnePosePerRobot) {
  TeamPicture picture = two_robot_picture();
  picture.truth.push_back({1.0, 1.0, 0.0});
  EXPECT_EQ(render_error(picture),
            "team picture: 3 true poses for 2 robots (one per robot, or none)");
}

TEST(TeamRender, ASolutionMustGiveOnePosePerRobot) {
  TeamPicture picture = two_robot_picture();
  picture.solutions[1].poses.pop_back();
  EXPECT_EQ(render_error(picture), "team picture: solution 1 has 1 pose for 2 robots");
}

TEST(TeamRender, ALinkMustNameRobotsOfThePicture) {
  TeamPicture picture = two_robot_picture();
  picture.links[1].to = 5;
  EXPECT_EQ(render_error(picture),
            "team picture: link 1 (1-5) names robot 5, but the picture has 2 robots (0 to 1)");
}

TEST(TeamRender, TheLinksUsedMustBeLinks) {
  TeamPicture picture = two_robot_picture();
  picture.links_used = {0, 2};
  EXPECT_EQ(render_error(picture), "team picture: links_used names link 2, but there are 2 links");
}

}  // namespace
}  // namespace gridloc::cli
