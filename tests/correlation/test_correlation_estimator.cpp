// Tests of engine/src/correlation/estimator.cpp: pose recovery on the bundled maps,
// multiresolution vs exhaustive agreement, and input validation.
#include "gridloc/engine/correlation/estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kSuccessXy = 0.10;
constexpr double kSuccessThetaDeg = 7.0;

double position_error(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}
double heading_error_deg(const Pose2& a, const Pose2& b) {
  return rad2deg(std::abs(normalize_angle(a.theta - b.theta)));
}

/// Maps and ring, loaded once for the whole file.
class Estimator : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ring_ = new SonarRing(load_sonar_ring(test::ring_path()));
    maps_ = new std::map<std::string, OccupancyMap>;
    for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
      (*maps_)[name] = load_ros_map(test::map_path(name));
    }
  }
  static void TearDownTestSuite() {
    delete ring_;
    delete maps_;
    ring_ = nullptr;
    maps_ = nullptr;
  }
  static const SonarRing& ring() { return *ring_; }
  static const OccupancyMap& map(const std::string& name) { return maps_->at(name); }

  static CorrelationOptions options(SearchStrategy strategy) {
    CorrelationOptions o;
    o.strategy = strategy;
    return o;
  }

 private:
  static inline SonarRing* ring_ = nullptr;
  static inline std::map<std::string, OccupancyMap>* maps_ = nullptr;
};

TEST_F(Estimator, ExhaustiveRecoversNoiseFreePoses) {
  int total_ok = 0, total = 0;
  std::uint64_t seed = 11;
  for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
    const CorrelationEstimator est(map(name), ring(), options(SearchStrategy::Exhaustive));
    Rng rng(seed++);
    int ok = 0;
    const int n = 10;
    for (int i = 0; i < n; ++i) {
      const Pose2 truth = sample_free_pose(map(name), ring(), 0.25, rng);
      const Observation obs{simulate_sonar(map(name), ring(), truth, SonarSimOptions{})};
      SearchWindow w;
      w.center = {truth.x + 0.3, truth.y - 0.2, normalize_angle(truth.theta + deg2rad(20.0))};
      const Estimate e = est.estimate(obs, w);
      const double dp = position_error(e.pose, truth), dt = heading_error_deg(e.pose, truth);
      const bool success = dp <= kSuccessXy && dt <= kSuccessThetaDeg;
      ok += success;
      if (!success) {
        std::cout << "[ miss ] " << name << " truth (" << truth.x << ", " << truth.y << ", "
                  << rad2deg(truth.theta) << " deg) -> (" << e.pose.x << ", " << e.pose.y << ", "
                  << rad2deg(e.pose.theta) << " deg): " << dp << " m, " << dt << " deg, confidence "
                  << e.confidence << "\n";
      }
    }
    std::cout << "[ info ] " << name << ": " << ok << "/" << n << " noise-free poses recovered\n";
    EXPECT_GE(ok, 9) << name;
    total_ok += ok;
    total += n;
  }
  EXPECT_GE(total_ok, total - 1);
}

TEST_F(Estimator, ExhaustiveEstimateIsConsistent) {
  const OccupancyMap& m = map("room_rect");
  const CorrelationEstimator est(m, ring(), options(SearchStrategy::Exhaustive));
  const Pose2 truth{3.0, 2.0, 0.0};
  const Observation obs{simulate_sonar(m, ring(), truth)};
  SearchWindow w;
  w.center = {3.2, 1.9, 0.2};
  const Estimate e = est.estimate(obs, w);
  EXPECT_LE(position_error(e.pose, truth), kSuccessXy);
  EXPECT_LE(heading_error_deg(e.pose, truth), kSuccessThetaDeg);
  // The window lies inside the map: 17 x 17 cells x 19 headings.
  EXPECT_EQ(e.stats.poses_scored, 17 * 17 * 19);
  EXPECT_EQ(e.stats.levels, 1);
  EXPECT_GT(e.stats.cells_scored, e.stats.poses_scored);
  EXPECT_GT(e.score, 0.0);
  EXPECT_GT(e.normalized_score, 0.0);
  EXPECT_LE(e.normalized_score, 1.0 + 1e-9);
  EXPECT_GE(e.confidence, 0.0);
  EXPECT_LE(e.confidence, 1.0);
  EXPECT_LE(e.second_score, e.score);
  ASSERT_FALSE(e.alternatives.empty());
  EXPECT_EQ(e.alternatives.front().pose.x, e.lattice_pose.x);
  EXPECT_EQ(e.alternatives.front().pose.y, e.lattice_pose.y);
  EXPECT_EQ(e.alternatives.front().pose.theta, e.lattice_pose.theta);
  EXPECT_EQ(e.alternatives.front().score, e.score);
  for (std::size_t i = 1; i < e.alternatives.size(); ++i) {
    EXPECT_LE(e.alternatives[i].score, e.alternatives[i - 1].score);
  }
  // The lattice pose lies on the lattice: cell centres of the 0.1 m grid, prior heading +
  // k * 5 deg; refinement stays within the winner's neighbourhood (one cell, 1.5 steps).
  const double gx = (e.lattice_pose.x - m.geometry.origin.x()) / 0.1 - 0.5;
  const double gy = (e.lattice_pose.y - m.geometry.origin.y()) / 0.1 - 0.5;
  EXPECT_NEAR(gx, std::round(gx), 1e-9);
  EXPECT_NEAR(gy, std::round(gy), 1e-9);
  const double k = (e.lattice_pose.theta - 0.2) / deg2rad(5.0);
  EXPECT_NEAR(k, std::round(k), 1e-9);
  EXPECT_LE(std::abs(e.pose.x - e.lattice_pose.x), 0.1 + 1e-9);
  EXPECT_LE(std::abs(e.pose.y - e.lattice_pose.y), 0.1 + 1e-9);
  EXPECT_LE(std::abs(normalize_angle(e.pose.theta - e.lattice_pose.theta)), deg2rad(7.5) + 1e-9);
  // Same input, same output.
  const Estimate again = est.estimate(obs, w);
  EXPECT_EQ(again.pose.x, e.pose.x);
  EXPECT_EQ(again.pose.y, e.pose.y);
  EXPECT_EQ(again.pose.theta, e.pose.theta);
  EXPECT_EQ(again.score, e.score);

  // Without refinement the pose is the lattice winner.
  CorrelationOptions o = options(SearchStrategy::Exhaustive);
  o.refine = false;
  const Estimate plain = CorrelationEstimator(m, ring(), o).estimate(obs, w);
  EXPECT_EQ(plain.pose.x, e.lattice_pose.x);
  EXPECT_EQ(plain.pose.y, e.lattice_pose.y);
  EXPECT_EQ(plain.pose.theta, e.lattice_pose.theta);
  EXPECT_EQ(plain.lattice_pose.x, e.lattice_pose.x);
  EXPECT_EQ(plain.score, e.score);
}

TEST_F(Estimator, RecoversPosesOnAYawedMap) {
  // room_rect placed in the world with a 90 deg yaw and an offset origin.
  OccupancyMap turned = map("room_rect");
  turned.geometry.origin = {4.0, -1.0};
  turned.geometry.yaw = std::numbers::pi / 2;
  const CorrelationEstimator est(turned, ring(), options(SearchStrategy::Exhaustive));
  for (const Pose2 grid_pose : {Pose2{3.5, 2.5, 0.0}, Pose2{2.0, 3.1, 2.3}}) {
    const Pose2 truth = turned.geometry.to_world_frame(grid_pose);
    const Observation obs{simulate_sonar(turned, ring(), truth)};
    SearchWindow w;
    w.center = {truth.x + 0.3, truth.y - 0.2, normalize_angle(truth.theta + deg2rad(20.0))};
    const Estimate e = est.estimate(obs, w);
    EXPECT_LE(position_error(e.pose, truth), kSuccessXy)
        << "(" << e.pose.x << ", " << e.pose.y << ") vs (" << truth.x << ", " << truth.y << ")";
    EXPECT_LE(heading_error_deg(e.pose, truth), kSuccessThetaDeg);
  }
}

TEST_F(Estimator, MultiresAgreesWithExhaustive) {
  int same = 0, total = 0;
  std::uint64_t seed = 21;
  for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
    const CorrelationEstimator exhaustive(map(name), ring(), options(SearchStrategy::Exhaustive));
    const CorrelationEstimator multires(map(name), ring(), options(SearchStrategy::Multires));
    EXPECT_EQ(multires.options().levels, 3);
    Rng rng(seed++);
    for (int i = 0; i < 10; ++i) {
      const Pose2 truth = sample_free_pose(map(name), ring(), 0.25, rng);
      const Observation obs{
          simulate_sonar(map(name), ring(), truth, SonarSimOptions::realistic(rng.next()))};
      SearchWindow w;
      w.center = {truth.x + rng.uniform(-0.6, 0.6), truth.y + rng.uniform(-0.6, 0.6),
                  normalize_angle(truth.theta + rng.uniform(-0.6, 0.6))};
      const Estimate a = exhaustive.estimate(obs, w);
      const Estimate b = multires.estimate(obs, w);
      EXPECT_GE(a.score, b.score);  // exhaustive is the maximum over the same lattice
      EXPECT_LT(b.stats.poses_scored, a.stats.poses_scored);
      EXPECT_EQ(b.stats.levels, 3);
      const bool agree =
          a.pose.x == b.pose.x && a.pose.y == b.pose.y && a.pose.theta == b.pose.theta;
      same += agree;
      ++total;
      if (!agree) {
        std::cout << "[ info ] " << name << ": multires (" << b.lattice_pose.x << ", "
                  << b.lattice_pose.y << ", " << rad2deg(b.lattice_pose.theta) << " deg, score "
                  << b.score << ") vs exhaustive (" << a.lattice_pose.x << ", " << a.lattice_pose.y
                  << ", " << rad2deg(a.lattice_pose.theta) << " deg, score " << a.score << ")\n";
      }
    }
  }
  std::cout << "[ info ] multires agrees with exhaustive on " << same << "/" << total << "\n";
  EXPECT_GE(same, (total * 8 + 9) / 10);
}

TEST_F(Estimator, LevelsAreBuiltAtTheirResolutions) {
  // Exact strategies search the finest grid only: they build no other.
  EXPECT_THROW(CorrelationEstimator(map("room_rect"), ring()).level(1), std::out_of_range);
  const CorrelationEstimator est(map("room_rect"), ring(), options(SearchStrategy::Multires));
  for (int l = 0; l < 3; ++l) {
    const PaddedGrid& p = est.level(l);
    EXPECT_NEAR(p.grid.geometry.resolution, 0.1 * (1 << l), 1e-12);
    // room_rect is 7.30 x 5.80 m.
    EXPECT_EQ(p.width, static_cast<int>(std::ceil(7.30 / (0.1 * (1 << l)) - 1e-9)));
    EXPECT_EQ(p.height, static_cast<int>(std::ceil(5.80 / (0.1 * (1 << l)) - 1e-9)));
    EXPECT_GE(p.pad, static_cast<int>(std::ceil(ring().reach() / (0.1 * (1 << l)))));
  }
  EXPECT_THROW(est.level(3), std::out_of_range);
}

// ---- bad input -------------------------------------------------------------------------

class EstimatorErrors : public Estimator {
 protected:
  void SetUp() override {
    est = std::make_unique<CorrelationEstimator>(map("room_rect"), ring(),
                                                 options(SearchStrategy::Exhaustive));
    obs.ranges = simulate_sonar(map("room_rect"), ring(), {3.0, 2.0, 0.0});
    window.center = {3.1, 2.1, 0.1};
  }
  std::unique_ptr<CorrelationEstimator> est;
  Observation obs;
  SearchWindow window;
};

TEST_F(EstimatorErrors, WrongReadingCount) {
  obs.ranges.pop_back();
  test::expect_error([&] { est->estimate(obs, window); }, {"expected 14", "got 13"});
}

TEST_F(EstimatorErrors, NaNReading) {
  obs.ranges[4] = std::numeric_limits<double>::quiet_NaN();
  test::expect_error([&] { est->estimate(obs, window); }, {"range 4", "NaN"});
}

TEST_F(EstimatorErrors, PriorOutsideTheMap) {
  window.center = {-3.0, 2.0, 0.0};
  test::expect_error([&] { est->estimate(obs, window); }, {"prior", "outside the map"});
  window.center = {3.0, 50.0, 0.0};
  test::expect_error([&] { est->estimate(obs, window); }, {"prior", "outside the map"});
  window.center = {std::numeric_limits<double>::quiet_NaN(), 2.0, 0.0};
  test::expect_error([&] { est->estimate(obs, window); }, {"prior", "finite"});
}

TEST_F(EstimatorErrors, BadWindow) {
  SearchWindow w = window;
  w.step_xy = 0.0;
  test::expect_error([&] { est->estimate(obs, w); }, {"step_xy"});
  w = window;
  w.half_xy = -0.1;
  test::expect_error([&] { est->estimate(obs, w); }, {"half_xy", "-0.1"});
  w = window;
  w.step_xy = 0.05;  // differs from the estimator's 0.1 m grid
  test::expect_error([&] { est->estimate(obs, w); }, {"step_xy", "0.05", "resolution"});
  w = window;
  w.step_theta = 0.0;
  test::expect_error([&] { est->estimate(obs, w); }, {"step_theta"});
  w = window;
  w.half_theta = 4.0;
  test::expect_error([&] { est->estimate(obs, w); }, {"half_theta"});
  w = window;
  w.half_xy = 50.0;  // the map is 7 x 5.5 m
  test::expect_error([&] { est->estimate(obs, w); }, {"larger than the map", "global"});
  // The whole-map window of global localization is the largest one accepted.
  EXPECT_NO_THROW(est->estimate(obs, est->global_window(obs)));
}

TEST_F(Estimator, BadOptions) {
  CorrelationOptions o;
  o.resolution = 0.0;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), o); }, {"resolution"});
  o = {};
  o.levels = 0;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), o); }, {"levels"});
  o = {};
  o.keep = 0;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), o); }, {"keep"});
  o = {};
  o.poses_per_thread = -1.0;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), o); },
                     {"poses_per_thread", "-1"});
  test::expect_error([&] { CorrelationEstimator(OccupancyMap{}, ring(), {}); }, {"empty"});
  CorrelationOptions hurried = options(SearchStrategy::Multires);
  hurried.budget_ms = 5.0;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), hurried); },
                     {"budget_ms", "branch-and-bound"});
  CorrelationOptions intervals = options(SearchStrategy::Exhaustive);
  intervals.heading_intervals = true;
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), ring(), intervals); },
                     {"heading_intervals", "branch-and-bound"});
  SonarRing empty;
  empty.name = "nothing";
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), empty, {}); },
                     {"nothing", "no sonars"});
  CorrelationOptions far;
  far.reach_m = 1e12;  // finite, but its padding would overflow the grid's int sizes
  test::expect_error([&] { CorrelationEstimator(map("room_rect"), far); },
                     {"reach", "million cells"});
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Scoring headings on several threads must not change a single bit of the answer.
TEST(CorrelationEstimatorThreads, TwoThreadsGiveTheSameEstimateAsOne) {
  const OccupancyMap map = load_ros_map(test::map_path("room_l"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  for (SearchStrategy strategy :
       {SearchStrategy::Multires, SearchStrategy::Exhaustive, SearchStrategy::BranchAndBound}) {
    CorrelationOptions one, two;
    one.strategy = two.strategy = strategy;
    two.threads = 2;
    two.poses_per_thread = 0.0;  // these small windows would run on one thread otherwise
    const CorrelationEstimator a(map, ring, one), b(map, ring, two);
    Rng rng(99);
    for (int t = 0; t < 5; ++t) {
      const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
      const Observation obs{
          simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()))};
      SearchWindow w;
      w.center = {truth.x + 0.3, truth.y - 0.2, truth.theta + 0.2};
      const Estimate ea = a.estimate(obs, w), eb = b.estimate(obs, w);
      EXPECT_EQ(ea.score, eb.score);
      EXPECT_EQ(ea.pose.x, eb.pose.x);
      EXPECT_EQ(ea.pose.y, eb.pose.y);
      EXPECT_EQ(ea.pose.theta, eb.pose.theta);
      EXPECT_EQ(ea.second_score, eb.second_score);
      if (strategy == SearchStrategy::BranchAndBound) continue;  // its work depends on timing
      EXPECT_EQ(ea.stats.poses_scored, eb.stats.poses_scored);
      EXPECT_EQ(ea.stats.cells_scored, eb.stats.cells_scored);
    }
  }
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Branch and bound is exact: the same lattice winner, score and second distinct score as
// the exhaustive search, on noisy observations in every room: with every hypothesis (floor
// 0: one search each after the winner), and with floors (one pass: the hypotheses that
// reach the floor's share of the winner, then the floor as a bound of the next).
TEST(CorrelationEstimatorBnb, EqualsExhaustive) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  int below_floor = 0;
  for (const double floor : {0.0, CorrelationOptions{}.second_peak_floor, 0.97}) {
    for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
      const OccupancyMap map = load_ros_map(test::map_path(name));
      CorrelationOptions exhaustive, bnb;
      exhaustive.strategy = SearchStrategy::Exhaustive;
      bnb.strategy = SearchStrategy::BranchAndBound;
      exhaustive.hypotheses = bnb.hypotheses = 4;  // the top 4 distinct poses, exactly
      exhaustive.second_peak_floor = bnb.second_peak_floor = floor;
      const CorrelationEstimator a(map, ring, exhaustive), b(map, ring, bnb);
      Rng rng(7);
      for (int t = 0; t < 6; ++t) {
        const std::string what =
            std::string(name) + " " + std::to_string(t) + " floor " + std::to_string(floor);
        const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
        const Observation obs{
            simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()))};
        SearchWindow w;
        w.center = {truth.x - 0.4, truth.y + 0.5, truth.theta - 0.3};
        const Estimate ea = a.estimate(obs, w), eb = b.estimate(obs, w);
        EXPECT_EQ(ea.lattice_pose.x, eb.lattice_pose.x) << what;
        EXPECT_EQ(ea.lattice_pose.y, eb.lattice_pose.y) << what;
        EXPECT_EQ(ea.lattice_pose.theta, eb.lattice_pose.theta) << what;
        EXPECT_EQ(ea.score, eb.score) << what;
        EXPECT_EQ(ea.second_score, eb.second_score) << what;
        EXPECT_EQ(ea.second_below_floor, eb.second_below_floor) << what;
        EXPECT_EQ(ea.confidence, eb.confidence) << what;
        EXPECT_EQ(ea.pose.x, eb.pose.x) << what;
        ASSERT_EQ(ea.alternatives.size(), eb.alternatives.size()) << what;
        if (floor == 0.0) {
          EXPECT_EQ(ea.alternatives.size(), 4u) << what;
        }
        for (std::size_t k = 0; k < ea.alternatives.size(); ++k) {
          EXPECT_EQ(ea.alternatives[k].score, eb.alternatives[k].score) << what;
          EXPECT_GE(ea.alternatives[k].score, floor * ea.score) << what;
          EXPECT_EQ(ea.alternatives[k].pose.x, eb.alternatives[k].pose.x) << what;
          EXPECT_EQ(ea.alternatives[k].pose.y, eb.alternatives[k].pose.y) << what;
          EXPECT_EQ(ea.alternatives[k].pose.theta, eb.alternatives[k].pose.theta) << what;
        }
        if (ea.second_below_floor) {
          ++below_floor;
          EXPECT_EQ(ea.second_score, floor * ea.score) << what;
          EXPECT_EQ(ea.alternatives.size(), 1u) << what;
        }
        EXPECT_LT(eb.stats.poses_scored, ea.stats.poses_scored) << what;
      }
    }
  }
  EXPECT_GT(below_floor, 0);  // the floor's branch ran
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// A budget makes branch and bound anytime: whatever it returns is a scored lattice pose
// no better than the optimum, with an upper bound no lower than it; proven means optimal.
TEST(CorrelationEstimatorBnb, BudgetReturnsTheBestSoFarAndWhatItProved) {
  const OccupancyMap map = load_ros_map(test::map_path("room_furnished"));
  const SonarRing ring = load_sonar_ring(test::ring_path());
  CorrelationOptions exact, hurried, single;
  exact.strategy = hurried.strategy = single.strategy = SearchStrategy::BranchAndBound;
  hurried.budget_ms = 1e-6;
  single.second_peak = false;
  const CorrelationEstimator a(map, ring, exact), b(map, ring, hurried), c(map, ring, single);
  Rng rng(5);
  for (int t = 0; t < 6; ++t) {
    const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
    const Observation obs{simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()))};
    SearchWindow w;
    w.center = {truth.x + 0.3, truth.y + 0.3, truth.theta + 0.3};
    const Estimate ea = a.estimate(obs, w), eb = b.estimate(obs, w), ec = c.estimate(obs, w);
    EXPECT_TRUE(ea.stats.proven_optimal);
    EXPECT_EQ(ea.stats.upper_bound, ea.score);
    EXPECT_LE(eb.score, ea.score) << t;
    EXPECT_GE(eb.stats.upper_bound, ea.score) << t;
    if (eb.stats.proven_optimal) {
      EXPECT_EQ(eb.lattice_pose.x, ea.lattice_pose.x) << t;
    }
    // Without the second search: the same winner; the second score, when the first search
    // scored a distinct pose at all, is a lower bound of the exact one.
    EXPECT_EQ(ec.lattice_pose.x, ea.lattice_pose.x) << t;
    EXPECT_EQ(ec.lattice_pose.theta, ea.lattice_pose.theta) << t;
    EXPECT_EQ(ec.score, ea.score) << t;
    if (ec.alternatives.size() > 1) {
      EXPECT_LE(ec.second_score, ea.second_score) << t;
    }
    EXPECT_LT(ec.stats.cells_scored, ea.stats.cells_scored) << t;
  }
}

TEST(CorrelationEstimatorErrors, TooManyHeadingsIsAnErrorNotAnAllocation) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  const CorrelationEstimator estimator(map, load_sonar_ring(test::ring_path()));
  SearchWindow w;
  w.center = {2.0, 2.0, 0.0};
  w.step_theta = 1e-9;
  const Observation obs{std::vector<double>(14, 2.0)};
  test::expect_error([&] { (void)estimator.estimate(obs, w); }, {"step_theta", "headings"});
}

}  // namespace
}  // namespace gridloc
