// The score volume of a window and the covariance of the peak (CorrelationEstimator).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(ScoreVolume, HoldsEveryPoseAndTheExactWinner) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Pose2 truth{2.4, 1.6, 0.3};
  const Observation obs{simulate_sonar(map, ring, truth)};
  SearchWindow w;
  w.center = {2.6, 1.5, 0.5};
  w.half_xy = 0.4;
  w.half_theta = 0.35;
  const CorrelationEstimator est(map, ring);  // bnb
  const ScoreVolume v = est.score_volume(obs, w);
  ASSERT_EQ(v.nx, 9);
  ASSERT_EQ(v.ny, 9);
  ASSERT_EQ(v.headings, 9);  // +-0.35 rad at 5 deg: +-4 steps
  ASSERT_EQ(v.scores.size(), 729u);
  ASSERT_EQ(v.mass.size(), 9u);
  // The volume's maximum is its winner, and the winner is the estimator's lattice pose.
  EXPECT_EQ(*std::max_element(v.scores.begin(), v.scores.end()), v.best.score);
  EXPECT_EQ(v.at(v.best.ix, v.best.iy, v.best.it), v.best.score);
  const Estimate e = est.estimate(obs, w);
  EXPECT_EQ(e.score, v.best.score);
  const Pose2 p = v.pose(v.best.ix, v.best.iy, v.best.it);
  EXPECT_NEAR(p.x, e.lattice_pose.x, 1e-9);
  EXPECT_NEAR(p.y, e.lattice_pose.y, 1e-9);
  EXPECT_NEAR(normalize_angle(p.theta - e.lattice_pose.theta), 0.0, 1e-9);
  for (double m : v.mass) EXPECT_GE(m, v.best.score);  // no score beats sum |L|
}

TEST(ScoreVolume, BadWindowIsTheSameErrorAsEstimate) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const CorrelationEstimator est(map, ring);
  SearchWindow w;
  w.center = {-50.0, 1.0, 0.0};
  test::expect_error(
      [&] {
        est.score_volume({simulate_sonar(map, ring, {2, 2, 0})}, w);
      },
      {"prior", "outside the map"});
}

/// A corridor along x: two walls 1.6 m apart, 12 m long, open (unknown) at both ends, so a
/// ring in its middle sees the same walls wherever it stands along it.
OccupancyMap corridor() {
  GridGeometry g;
  g.resolution = 0.05;
  g.width = 240;
  g.height = 40;
  OccupancyMap m(g, CellState::Free);
  for (int ix = 0; ix < g.width; ++ix) {
    for (int iy : {3, 4, 35, 36}) m.at(ix, iy) = CellState::Occupied;
    for (int iy : {0, 1, 2, 37, 38, 39}) m.at(ix, iy) = CellState::Unknown;
  }
  return m;
}

TEST(PeakCovariance, LargerAlongACorridorThanAcrossIt) {
  const OccupancyMap map = corridor();
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Pose2 truth{6.0, 1.04, 0.0};  // near a cell centre across (0.1 m cells)
  const Observation obs{simulate_sonar(map, ring, truth)};
  SearchWindow w;
  w.center = {6.1, 1.05, 0.05};
  for (SearchStrategy s : {SearchStrategy::BranchAndBound, SearchStrategy::Exhaustive}) {
    CorrelationOptions o;
    o.strategy = s;
    const Estimate e = CorrelationEstimator(map, ring, o).estimate(obs, w);
    const Eigen::Matrix3d& c = e.covariance;
    EXPECT_GT(c(0, 0), 4.0 * c(1, 1)) << to_string(s) << "\n" << c;
    EXPECT_TRUE(c.isApprox(c.transpose())) << c;
    EXPECT_GT(c.determinant(), 0.0) << c;  // positive definite: the quantization floor
    EXPECT_NEAR(e.pose.y, truth.y, 0.1);   // across the corridor the walls pin it down
  }
}

// Issue 19: where the corridor ends in a wall (a corner each side) the same ring is pinned
// along it too: the covariance along shrinks to within a few times the one across, far below
// the open corridor's.
TEST(PeakCovariance, ACorridorsEndPinsItAlongToo) {
  const OccupancyMap open = corridor();
  OccupancyMap closed = open;
  for (int iy = 3; iy <= 36; ++iy) {
    for (int ix : {150, 151}) closed.at(ix, iy) = CellState::Occupied;
  }
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Pose2 truth{6.9, 1.04, 0.0};  // the end wall 0.6 m ahead
  SearchWindow w;
  w.center = {6.95, 1.05, 0.05};
  const Estimate along =
      CorrelationEstimator(open, ring).estimate(Observation{simulate_sonar(open, ring, truth)}, w);
  const Estimate pinned = CorrelationEstimator(closed, ring)
                              .estimate(Observation{simulate_sonar(closed, ring, truth)}, w);
  const Eigen::Matrix3d& c = pinned.covariance;
  EXPECT_LT(c(0, 0), 4.0 * c(1, 1)) << c;
  EXPECT_LT(c(0, 0), 0.25 * along.covariance(0, 0)) << c << "\n" << along.covariance;
  EXPECT_NEAR(pinned.pose.x, truth.x, 0.1);
  EXPECT_NEAR(pinned.pose.y, truth.y, 0.1);
}

TEST(PeakCovariance, ATemperatureAboveOneCountsTheNeighboursBelowTheBest) {
  const OccupancyMap map = corridor();
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Observation obs{simulate_sonar(map, ring, {6.0, 1.04, 0.0})};
  SearchWindow w;
  w.center = {6.1, 1.05, 0.05};
  CorrelationOptions cold, hot;
  cold.ring_covariance_temperature = hot.ring_covariance_temperature = 0.0;  // report at T
  hot.covariance_temperature = 10.0;
  const Estimate a = CorrelationEstimator(map, ring, cold).estimate(obs, w);
  const Estimate b = CorrelationEstimator(map, ring, hot).estimate(obs, w);
  EXPECT_EQ(a.pose.x, b.pose.x);  // the same winner: only the covariance changes
  // Along the corridor every pose within covariance_cells scores alike, whatever the
  // temperature; across it and in heading the neighbours below the best now count.
  EXPECT_NEAR(b.covariance(0, 0), a.covariance(0, 0), 1e-12);
  EXPECT_GT(b.covariance(1, 1), 1.5 * a.covariance(1, 1)) << a.covariance << "\n" << b.covariance;
  EXPECT_GT(b.covariance(2, 2), 1.5 * a.covariance(2, 2)) << a.covariance << "\n" << b.covariance;
  for (double bad : {0.0, -1.0, std::nan("")}) {
    hot.covariance_temperature = bad;
    test::expect_error([&] { CorrelationEstimator(map, ring, hot); }, {"covariance_temperature"});
  }
}

// A sonar ring reports its covariance at ring_covariance_temperature; the verdict reads the
// spread at covariance_temperature, so the pose, the confidence and the verdict stay. A scan
// reports at covariance_temperature.
TEST(PeakCovariance, ARingReportsItsOwnTemperatureAndNoVerdictChanges) {
  const OccupancyMap map = corridor();
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Pose2 truth{6.0, 1.04, 0.0};
  const Observation obs{simulate_sonar(map, ring, truth)};
  SearchWindow w;
  w.center = {6.1, 1.05, 0.05};
  CorrelationOptions same, sharp;
  same.ring_covariance_temperature = 0.0;
  sharp.ring_covariance_temperature = 0.15;
  const Estimate a = CorrelationEstimator(map, ring, same).estimate(obs, w);
  const Estimate b = CorrelationEstimator(map, ring, sharp).estimate(obs, w);
  EXPECT_EQ(a.pose.x, b.pose.x);
  EXPECT_EQ(a.pose.y, b.pose.y);
  EXPECT_EQ(a.confidence, b.confidence);
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(a.confidence_parts.spread_m, b.confidence_parts.spread_m);
  EXPECT_NEAR(a.confidence_parts.spread_m, std::sqrt(a.covariance(0, 0) + a.covariance(1, 1)),
              1e-12);
  // Along the corridor every pose scores alike at any temperature; across it and in heading
  // the colder weights narrow the covariance reported.
  EXPECT_NEAR(b.covariance(0, 0), a.covariance(0, 0), 1e-12);
  EXPECT_LT(b.covariance(1, 1), 0.9 * a.covariance(1, 1)) << a.covariance << "\n" << b.covariance;
  EXPECT_LT(b.covariance(2, 2), 0.9 * a.covariance(2, 2)) << a.covariance << "\n" << b.covariance;

  Observation scan;
  scan.scan = simulate_scan(map, truth, 180, 4.0, 0.01, 7);
  CorrelationOptions same_scan = same, sharp_scan = sharp;
  same_scan.reach_m = sharp_scan.reach_m = 4.0;
  const Estimate c = CorrelationEstimator(map, same_scan).estimate(scan, w);
  const Estimate d = CorrelationEstimator(map, sharp_scan).estimate(scan, w);
  EXPECT_TRUE(c.covariance.isApprox(d.covariance, 1e-12)) << c.covariance << "\n" << d.covariance;

  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    sharp.ring_covariance_temperature = bad;
    test::expect_error([&] { CorrelationEstimator(map, ring, sharp); },
                       {"ring_covariance_temperature"});
  }
}

// A scan's refined pose reports scan_quantization_share of the lattice's quantization
// variance (step^2 / 12 per axis): the difference from keeping all of it is exactly the rest,
// and the pose, the spread and the verdict stay; a sonar ring keeps all of it unless its
// own share, ring_quantization_share, says otherwise.
TEST(PeakCovariance, AScanReportsItsShareOfTheQuantizationVariance) {
  const OccupancyMap map = corridor();
  const Pose2 truth{6.0, 1.04, 0.0};
  Observation scan;
  scan.scan = simulate_scan(map, truth, 180, 4.0, 0.01, 7);
  SearchWindow w;
  w.center = {6.1, 1.05, 0.05};
  CorrelationOptions all, half;
  all.reach_m = half.reach_m = 4.0;
  all.scan_quantization_share = 1.0;
  half.scan_quantization_share = 0.5;
  const Estimate a = CorrelationEstimator(map, all).estimate(scan, w);
  const Estimate b = CorrelationEstimator(map, half).estimate(scan, w);
  EXPECT_EQ(a.pose.x, b.pose.x);
  EXPECT_EQ(a.confidence_parts.spread_m, b.confidence_parts.spread_m);
  EXPECT_EQ(a.verdict, b.verdict);
  const double res = all.resolution, step = w.step_theta;  // the window's lattice
  Eigen::Matrix3d rest = Eigen::Matrix3d::Zero();
  rest.diagonal() << 0.5 * res * res / 12.0, 0.5 * res * res / 12.0, 0.5 * step * step / 12.0;
  EXPECT_TRUE((a.covariance - b.covariance).isApprox(rest, 1e-9))
      << a.covariance - b.covariance << "\n"
      << rest;
  // Not refined: the pose is a lattice pose, its whole quantization error stays.
  all.refine = half.refine = false;
  EXPECT_TRUE(CorrelationEstimator(map, all).estimate(scan, w).covariance.isApprox(
      CorrelationEstimator(map, half).estimate(scan, w).covariance, 1e-12));
  // A ring keeps all of it.
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const Observation firing{simulate_sonar(map, ring, truth)};
  all.refine = half.refine = true;
  all.reach_m = half.reach_m = 0.0;
  EXPECT_TRUE(CorrelationEstimator(map, ring, all)
                  .estimate(firing, w)
                  .covariance.isApprox(
                      CorrelationEstimator(map, ring, half).estimate(firing, w).covariance, 1e-12));
  // ... unless told by its own share, ring_quantization_share, the same way.
  CorrelationOptions ring_half = half;
  ring_half.ring_quantization_share = 0.5;
  const Estimate whole = CorrelationEstimator(map, ring, all).estimate(firing, w);
  const Estimate shared = CorrelationEstimator(map, ring, ring_half).estimate(firing, w);
  EXPECT_EQ(whole.pose.x, shared.pose.x);
  EXPECT_EQ(whole.verdict, shared.verdict);
  EXPECT_TRUE((whole.covariance - shared.covariance).isApprox(rest, 1e-9))
      << whole.covariance - shared.covariance;
  for (double bad : {-0.1, 1.5, std::nan("")}) {
    half.scan_quantization_share = bad;
    test::expect_error([&] { CorrelationEstimator(map, ring, half); }, {"scan_quantization_share"});
    ring_half.ring_quantization_share = bad;
    test::expect_error([&] { CorrelationEstimator(map, ring, ring_half); },
                       {"ring_quantization_share"});
  }
}

TEST(PeakCovariance, OffMeansZero) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  CorrelationOptions o;
  o.covariance_cells = 0;
  SearchWindow w;
  w.center = {2.5, 1.5, 0.3};
  const Estimate e =
      CorrelationEstimator(map, ring, o).estimate({simulate_sonar(map, ring, {2.4, 1.6, 0.3})}, w);
  EXPECT_TRUE(e.covariance.isZero());
  o.covariance_cells = -1;
  test::expect_error([&] { CorrelationEstimator(map, ring, o); }, {"covariance_cells"});
}

}  // namespace
}  // namespace gridloc
