// Tests of the ICP estimators (engine/src/icp/estimator.cpp, map_contour.cpp): scan-to-map ICP
// recovers a pose from a laser scan, correlation + ICP refines the search's winner, the
// contour's normals are those of the walls, and sonar input or bad options are refused.
#include "gridloc/engine/icp/estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/scan_map.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

double pos_err(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
double ang_err(const Pose2& a, const Pose2& b) {
  return std::abs(normalize_angle(a.theta - b.theta));
}

Observation laser_at(const OccupancyMap& map, const Pose2& pose, double sigma, std::uint64_t seed) {
  Observation obs;
  obs.scan = simulate_scan(map, pose, 360, 8.0, sigma, seed);
  return obs;
}

TEST(MapContour, NormalsAreTheWalls) {
  // A 4 m x 3 m box room at 0.05 m: contour points on the long walls have vertical normals.
  GridGeometry g;
  g.resolution = 0.05;
  g.width = 80;
  g.height = 60;
  OccupancyMap map(g, CellState::Free);
  for (int x = 0; x < g.width; ++x) map.at(x, 0) = map.at(x, g.height - 1) = CellState::Occupied;
  for (int y = 0; y < g.height; ++y) map.at(0, y) = map.at(g.width - 1, y) = CellState::Occupied;
  const MapContour contour(map);
  ASSERT_GT(contour.size(), 200u);
  int checked = 0;
  for (std::size_t i = 0; i < contour.size(); ++i) {
    const Eigen::Vector2d& p = contour.points()[i];
    if (p.y() < 0.1 && p.x() > 0.5 && p.x() < 3.5) {
      EXPECT_NEAR(std::abs(contour.normals()[i].y()), 1.0, 1e-9) << p.transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
  test::expect_error([&] { MapContour(OccupancyMap{}); }, {"empty"});
  MapContourOptions bad;
  bad.normal_radius_m = 0.0;
  test::expect_error([&] { MapContour(map, bad); }, {"normal_radius_m"});
}

TEST(IcpEstimator, RecoversThePoseFromAPriorOffBy20CmAnd6Deg) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  const IcpEstimator icp(map);
  for (const Pose2 truth : {Pose2{2.0, 2.0, 0.3}, Pose2{6.5, 4.5, -2.0}, Pose2{8.0, 1.5, 1.2}}) {
    SearchWindow w;
    w.center = {truth.x + 0.15, truth.y - 0.12, truth.theta + 0.1};
    const Estimate e = icp.estimate(laser_at(map, truth, 0.01, 7), w);
    EXPECT_LT(pos_err(e.pose, truth), 0.02) << truth.x << "," << truth.y;
    EXPECT_LT(ang_err(e.pose, truth), 0.01);
    EXPECT_EQ(e.verdict, Verdict::Localized);
    EXPECT_FALSE(e.on_window_edge);
    EXPECT_GT(e.confidence_parts.fit, 0.8);
    EXPECT_GT(e.covariance(0, 0), 0.0);
    EXPECT_LT(e.covariance(0, 0), 1e-3);
  }
}

TEST(IcpEstimator, AMapFarFromItsOriginWorksAsWell) {
  // The same map 1 km from its frame's origin (UTM-like coordinates): the increment turns
  // about the robot, not the origin, so ICP converges the same way.
  OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  const Pose2 near_truth{6.5, 4.5, -2.0};
  const Eigen::Vector2d shift(1000.0, 1000.0);
  map.geometry.origin += shift;
  const IcpEstimator icp(map);
  const Pose2 truth{near_truth.x + shift.x(), near_truth.y + shift.y(), near_truth.theta};
  SearchWindow w;
  w.center = {truth.x + 0.15, truth.y - 0.12, truth.theta + 0.1};
  const Estimate e = icp.estimate(laser_at(map, truth, 0.01, 7), w);
  EXPECT_LT(pos_err(e.pose, truth), 0.02);
  EXPECT_LT(ang_err(e.pose, truth), 0.01);
  EXPECT_EQ(e.verdict, Verdict::Localized);
}

TEST(IcpEstimator, AScanTooSparseForIcpIsNotLocalizedNotAnError) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  const IcpEstimator icp(map);
  SearchWindow w;
  w.center = {2.0, 2.0, 0.3};
  Observation sparse;
  sparse.scan = simulate_scan(map, w.center, 12, 8.0, 0.0, 1);  // 30 deg apart: no segments
  const Estimate e = icp.estimate(sparse, w);
  EXPECT_EQ(e.verdict, Verdict::NotLocalized);
  EXPECT_EQ(e.confidence, 0.0);
  EXPECT_TRUE(std::isinf(e.covariance(0, 0)));
  EXPECT_EQ(e.covariance(0, 1), 0.0);  // no NaN from inf * 0
}

TEST(IcpEstimator, APoseLeavingTheWindowIsNotLocalized) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  const IcpEstimator icp(map);
  const Pose2 truth{2.0, 2.0, 0.3};
  SearchWindow w;
  w.center = {truth.x + 0.15, truth.y, truth.theta};
  w.half_xy = 0.05;  // ICP walks 15 cm to the truth: out of this window
  const Estimate e = icp.estimate(laser_at(map, truth, 0.0, 1), w);
  EXPECT_TRUE(e.on_window_edge);
  EXPECT_EQ(e.verdict, Verdict::NotLocalized);
}

TEST(IcpEstimator, CorrelationThenIcpBeatsTheLattice) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  CorrelationOptions co;
  co.resolution = 0.05;
  co.reach_m = 8.0;
  auto correlation = std::make_shared<const CorrelationEstimator>(map, co);
  auto icp = std::make_shared<const IcpEstimator>(map);
  const CorrelationIcpEstimator both(correlation, icp);
  EXPECT_EQ(both.name(), "correlation+icp");
  const Pose2 truth{6.5, 4.5, -2.0};
  SearchWindow w;
  // A prior ICP alone cannot come back from: 0.5 m and 25 deg off.
  w.center = {truth.x + 0.4, truth.y + 0.3, truth.theta + 0.44};
  w.half_xy = 0.6;
  w.half_theta = 0.6;
  w.step_xy = 0.05;
  w.step_theta = 0.02;
  const Observation obs = laser_at(map, truth, 0.01, 3);
  const Estimate c = correlation->estimate(obs, w);
  const Estimate e = both.estimate(obs, w);
  EXPECT_LT(pos_err(e.pose, truth), 0.02);
  EXPECT_LT(ang_err(e.pose, truth), 0.01);
  EXPECT_LE(pos_err(e.pose, truth), pos_err(c.pose, truth) + 1e-9);
  EXPECT_EQ(e.confidence, c.confidence);  // the search's confidence
}

TEST(IcpEstimator, RefusesSonarAndBadOptions) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  const IcpEstimator icp(map);
  Observation sonar;
  sonar.ranges = {1.0, 2.0, 3.0};
  SearchWindow w;
  w.center = {2.0, 2.0, 0.0};
  test::expect_error([&] { icp.estimate(sonar, w); }, {"laser scan", "sonar"});
  Observation nan_scan = laser_at(map, {2.0, 2.0, 0.0}, 0.0, 1);
  nan_scan.scan->ranges[3] = std::nan("");
  test::expect_error([&] { icp.estimate(nan_scan, w); }, {"range"});
  IcpEstimatorOptions bad;
  bad.icp.max_correspondence_m = -1.0;
  test::expect_error([&] { IcpEstimator(map, bad); }, {"max_correspondence_m"});
}

TEST(ScanMap, ReturnsAreOccupiedAndBeamsFree) {
  RangeScan scan;
  scan.max_range = 10.0;
  for (int k = 0; k < 180; ++k) {
    scan.angles.push_back(-M_PI / 2 + k * M_PI / 180.0);
    // Beams 85-95 (around straight ahead) have no return.
    scan.ranges.push_back(k >= 85 && k <= 95 ? 10.0 : 3.0);
  }
  const OccupancyMap map = scan_occupancy_map(scan, 0.1);
  const GridGeometry& g = map.geometry;
  auto state = [&](double x, double y) {
    const Cell c = g.cell_of(x - g.origin.x(), y - g.origin.y());
    return map.at(c.ix, c.iy);
  };
  EXPECT_EQ(state(0.02, -2.98), CellState::Occupied);  // beam 0 (-90 deg) ends at (0, -3)
  EXPECT_EQ(state(0.02, -1.5), CellState::Free);
  EXPECT_EQ(state(2.5, 0.0), CellState::Unknown);    // no return: unknown, not free
  EXPECT_EQ(state(-1.0, -1.0), CellState::Unknown);  // behind the 180 deg field
  const double a17 = scan.angles[107];               // 17 deg
  EXPECT_EQ(state(3.0 * std::cos(a17), 3.0 * std::sin(a17)), CellState::Occupied);
  test::expect_error([&] { scan_occupancy_map(scan, 0.0); }, {"resolution"});
  test::expect_error([&] { scan_occupancy_map(scan, 0.1, -1.0); }, {"margin"});
}

}  // namespace
}  // namespace gridloc
