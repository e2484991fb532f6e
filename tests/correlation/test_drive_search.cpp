// The correlation search on local grids grown along a short drive (issue 13): a drive's
// firings fused into one virtual ring (sensors/drive_fusion.hpp) are matched by the same
// exact search, which finds the latest firing's pose.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const SonarRing& ring() {
  static const SonarRing loaded = load_sonar_ring(test::ring_path());
  return loaded;
}

/// Whether the map cell under a pose is free.
bool on_free_cell(const OccupancyMap& map, const Pose2& pose) {
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(local.x, local.y);
  return map.geometry.contains(cell.ix, cell.iy) && map.at(cell.ix, cell.iy) == CellState::Free;
}

/// A drive that ends at a free pose: `firings` firings `step_m` apart along its heading
/// (reversing from the end), each with realistic sonar noise; exact odometry. Empty when a
/// firing would stand on a wall.
std::vector<OdometryFiring> drive_to(const OccupancyMap& map, const Pose2& latest, int firings,
                                     double step_m, std::uint64_t seed) {
  std::vector<OdometryFiring> drive;
  for (int k = firings - 1; k >= 0; --k) {
    const Pose2 pose = compose(latest, {-step_m * k, 0.0, 0.0});
    if (!on_free_cell(map, pose)) return {};
    drive.push_back(
        {pose, simulate_sonar(map, ring(), pose, SonarSimOptions::realistic(seed + 97 * k))});
  }
  return drive;
}

struct DriveCase {
  Pose2 truth;
  FusedFirings fused;
};

/// Drives of three firings 0.4 m apart ending at random free poses of `map`.
std::vector<DriveCase> drive_cases(const OccupancyMap& map, int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<DriveCase> cases;
  while (static_cast<int>(cases.size()) < count) {
    const Pose2 truth = sample_free_pose(map, ring(), 0.25, rng);
    const std::vector<OdometryFiring> drive = drive_to(map, truth, 3, 0.4, rng.next());
    if (!drive.empty()) cases.push_back({truth, fuse_firings(ring(), drive)});
  }
  return cases;
}

/// Branch and bound's answer is the exhaustive reference's, proven optimal.
void expect_same_winner(const Estimate& fast, const Estimate& reference) {
  EXPECT_EQ(fast.score, reference.score);
  EXPECT_EQ(fast.lattice_pose.x, reference.lattice_pose.x);
  EXPECT_EQ(fast.lattice_pose.y, reference.lattice_pose.y);
  EXPECT_EQ(fast.lattice_pose.theta, reference.lattice_pose.theta);
  EXPECT_TRUE(fast.stats.proven_optimal);
}

SearchWindow window_at(const Pose2& center) {
  SearchWindow window;
  window.center = center;
  return window;
}

TEST(DriveSearch, BranchAndBoundEqualsExhaustiveOnAFusedDrive) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  for (const DriveCase& drive : drive_cases(map, 4, 5)) {
    CorrelationOptions options;
    options.strategy = SearchStrategy::BranchAndBound;
    const CorrelationEstimator bnb(map, drive.fused.ring, options);
    options.strategy = SearchStrategy::Exhaustive;
    const CorrelationEstimator exhaustive(map, drive.fused.ring, options);
    const Observation observation{drive.fused.ranges};
    const Pose2 prior = compose(drive.truth, {0.3, -0.2, 0.2});
    const Estimate fast = bnb.estimate(observation, window_at(prior));
    const Estimate reference = exhaustive.estimate(observation, window_at(prior));
    expect_same_winner(fast, reference);
  }
}

TEST(DriveSearch, OneEstimatorServesEveryDriveThroughTheObservationsRing) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  CorrelationOptions options;
  options.reach_m = ring().reach() + DriveWindowOptions{}.max_distance_m;
  const CorrelationEstimator shared(map, ring(), options);
  for (const DriveCase& drive : drive_cases(map, 3, 23)) {
    const CorrelationEstimator own(map, drive.fused.ring);
    const Pose2 prior = compose(drive.truth, {0.2, 0.3, -0.3});
    const Estimate expected = own.estimate(Observation{drive.fused.ranges}, window_at(prior));
    const Observation observation{drive.fused.ranges, std::nullopt, {}, drive.fused.ring};
    const Estimate e = shared.estimate(observation, window_at(prior));
    EXPECT_EQ(e.score, expected.score);
    EXPECT_EQ(e.lattice_pose.x, expected.lattice_pose.x);
    EXPECT_EQ(e.lattice_pose.y, expected.lattice_pose.y);
    EXPECT_EQ(e.lattice_pose.theta, expected.lattice_pose.theta);
    EXPECT_EQ(e.agreement, expected.agreement);
  }
  // A drive longer than the estimator's reach allows is refused, not cut.
  const CorrelationEstimator short_reach(map, ring());
  const DriveCase drive = drive_cases(map, 1, 29).front();
  const Observation too_far{drive.fused.ranges, std::nullopt, {}, drive.fused.ring};
  test::expect_error([&] { short_reach.estimate(too_far, window_at(drive.truth)); },
                     {"drive's ring reaches", "reach_m"});
}

TEST(DriveSearch, ADriveLocalizesItsLatestPose) {
  const OccupancyMap map = load_ros_map(test::map_path("room_furnished"));
  for (const DriveCase& drive : drive_cases(map, 6, 11)) {
    const CorrelationEstimator estimator(map, drive.fused.ring);
    const Pose2 prior = compose(drive.truth, {-0.4, 0.3, -0.4});
    const Estimate e = estimator.estimate(Observation{drive.fused.ranges}, window_at(prior));
    EXPECT_LE(std::hypot(e.pose.x - drive.truth.x, e.pose.y - drive.truth.y), 0.10);
    EXPECT_LE(std::abs(normalize_angle(e.pose.theta - drive.truth.theta)), deg2rad(7.0));
  }
}

/// A corridor 16 m long and 2 m wide (5 cm cells, walls 0.15 m), with a 1 m wide, 0.8 m deep
/// recess in its north wall 2.5-3.5 m from the west end: away from the recess and the ends,
/// every place of the corridor reads the same.
OccupancyMap corridor_with_recess() {
  OccupancyMap map;
  map.geometry.resolution = 0.05;
  map.geometry.origin = {-0.5, -0.5};
  map.geometry.width = 340;  // 17 m
  map.geometry.height = 80;  // 4 m
  map.cells.assign(map.geometry.size(), CellState::Unknown);
  const auto inside = [](double x, double y, double x0, double y0, double x1, double y1) {
    return x >= x0 && x < x1 && y >= y0 && y < y1;
  };
  for (int iy = 0; iy < map.geometry.height; ++iy) {
    for (int ix = 0; ix < map.geometry.width; ++ix) {
      const double x = -0.5 + (ix + 0.5) * 0.05, y = -0.5 + (iy + 0.5) * 0.05;
      const bool corridor = inside(x, y, 0.0, 0.0, 16.0, 2.0);
      const bool recess = inside(x, y, 2.5, 2.0, 3.5, 2.8);
      const bool walls =
          inside(x, y, -0.15, -0.15, 16.15, 2.15) || inside(x, y, 2.35, 2.0, 3.65, 2.95);
      map.at(ix, iy) = corridor || recess ? CellState::Free
                       : walls            ? CellState::Occupied
                                          : CellState::Unknown;
    }
  }
  return map;
}

TEST(DriveSearch, ACorridorAmbiguousFromOneFiringIsResolvedByADrive) {
  const OccupancyMap map = corridor_with_recess();
  const Pose2 latest{5.5, 1.0, 0.0};
  // Seven firings over the last 3 m, the first ones beside the recess; noise-free readings.
  std::vector<OdometryFiring> drive;
  for (int k = 0; k < 7; ++k) {
    const Pose2 pose{2.5 + 0.5 * k, 1.0, 0.0};
    drive.push_back({pose, simulate_sonar(map, ring(), pose, SonarSimOptions{})});
  }
  // One firing: the corridor reads the same in many places, and the best two are tied.
  const CorrelationEstimator standstill(map, ring());
  const Observation one{drive.back().ranges};
  const Estimate alone = standstill.estimate(one, standstill.global_window(one));
  EXPECT_EQ(alone.verdict, Verdict::Ambiguous);
  ASSERT_GE(alone.alternatives.size(), 2u);
  EXPECT_EQ(alone.alternatives[0].score, alone.alternatives[1].score);

  // The drive: the recess its first firings saw pins the place and the heading.
  DriveWindowOptions window;
  window.max_distance_m = 3.0;  // exact odometry: the whole drive
  const FusedFirings fused = fuse_firings(ring(), drive, window);
  ASSERT_EQ(fused.firings, 7u);
  const CorrelationEstimator driving(map, fused.ring);
  const Observation all{fused.ranges};
  const Estimate e = driving.estimate(all, driving.global_window(all));
  EXPECT_LE(std::hypot(e.lattice_pose.x - latest.x, e.lattice_pose.y - latest.y), 0.10);
  EXPECT_LE(std::abs(normalize_angle(e.lattice_pose.theta - latest.theta)), deg2rad(7.0));
  ASSERT_GE(e.alternatives.size(), 2u);
  EXPECT_GT(e.alternatives[0].score, e.alternatives[1].score);
  // Not asserted, measured: the verdict stays `ambiguous`. The corridor turned about its
  // centre scores 98.4 % of the winner (197.99 against 201.22), above the 97 % rule, which is
  // relative: more firings add the same evidence to both and dilute the recess's few cells.
  // The refined pose (5.388, 0.952) also slides 11 cm along the corridor from the lattice
  // winner (5.45, 0.95). Hypotheses re-scored through motion (issue 13) are to decide it.
}

TEST(DriveSearch, BranchAndBoundEqualsExhaustiveOnFusedScans) {
  const OccupancyMap map = load_ros_map(test::map_path("apartment_small"));
  Rng rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    const Pose2 truth = sample_free_pose(map, ring(), 0.25, rng);
    std::vector<OdometryScan> drive;
    for (int k = 2; k >= 0; --k) {
      const Pose2 pose = compose(truth, {-0.3 * k, 0.0, -0.1 * k});
      drive.push_back({pose, simulate_scan(map, pose, 90, 6.0, 0.02, rng.next())});
    }
    Observation observation;
    observation.points = fuse_scans(drive, {0.1, 0.0, 0.0}, {}).points;
    CorrelationOptions options;
    options.resolution = map.geometry.resolution;
    options.reach_m = 8.0;
    options.strategy = SearchStrategy::BranchAndBound;
    const CorrelationEstimator bnb(map, options);
    options.strategy = SearchStrategy::Exhaustive;
    const CorrelationEstimator exhaustive(map, options);
    SearchWindow window = window_at(compose(truth, {0.2, -0.1, 0.1}));
    window.half_xy = 0.3;
    window.half_theta = 0.3;
    window.step_xy = options.resolution;
    window.step_theta = deg2rad(2.0);
    const Estimate fast = bnb.estimate(observation, window);
    const Estimate reference = exhaustive.estimate(observation, window);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_same_winner(fast, reference);
  }
}

TEST(DriveSearch, ScanPointsMustBeAloneFiniteAndWithinReach) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  CorrelationOptions options;
  options.reach_m = 4.0;
  const CorrelationEstimator estimator(map, options);
  const SearchWindow window = window_at({2.0, 1.5, 0.0});
  std::vector<OdometryScan> drive = {
      {{0.0, 0.0, 0.0}, simulate_scan(map, {2.0, 1.5, 0.0}, 90, 3.0, 0.0, 1)}};
  Observation observation;
  observation.points = fuse_scans(drive, {}, {}).points;
  EXPECT_NO_THROW(estimator.estimate(observation, window));
  observation.points->x[3] = std::nan("");
  test::expect_error([&] { estimator.estimate(observation, window); }, {"point 3", "finite"});
  observation.points = fuse_scans(drive, {3.0, 0.0, 0.0}, {}).points;  // beyond the reach
  test::expect_error([&] { estimator.estimate(observation, window); }, {"reach"});
  observation.points = fuse_scans(drive, {}, {}).points;
  observation.ranges = {1.0};
  test::expect_error([&] { estimator.estimate(observation, window); }, {"scan points alone"});
}

}  // namespace
}  // namespace gridloc
