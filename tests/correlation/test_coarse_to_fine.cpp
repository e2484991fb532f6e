// The coarse-to-fine global search (issue 35): a coarse copy's places refined at the map's
// cell find what the exact search finds on simulated scans, say they are not proven optimal,
// keep the exact search's verdict rules, and refuse bad options.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>

#include "gridloc/engine/correlation/coarse_to_fine.hpp"
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kMaxRange = 8.0;

std::shared_ptr<const CorrelationEstimator> laser_estimator(const std::string& map_name,
                                                            bool second_peak = true,
                                                            int max_bound_depth = 0) {
  CorrelationOptions options;
  options.max_bound_depth = max_bound_depth;
  options.global = GlobalModel::LikelihoodField;
  options.resolution = 0.05;
  options.reach_m = kMaxRange;
  options.second_peak = second_peak;
  return std::make_shared<const CorrelationEstimator>(load_ros_map(test::map_path(map_name)),
                                                      options);
}

Observation scan_at(const OccupancyMap& map, const Pose2& pose, std::uint64_t seed) {
  Observation observation;
  observation.scan = simulate_scan(map, pose, 180, kMaxRange, 0.01, seed);
  return observation;
}

/// A free pose drawn on `map`, its scan and the whole map's window.
struct Trial {
  Pose2 truth;
  Observation observation;
  SearchWindow whole;
};

Trial trial_on(const CorrelationEstimator& fine, Rng& rng) {
  Trial t;
  t.truth = sample_free_pose(fine.map(), SonarRing{}, 0.4, rng);
  t.observation = scan_at(fine.map(), t.truth, rng.next());
  t.whole = fine.global_window(t.observation);
  return t;
}

/// Runs `a` and `b` on `trials` scans simulated on `on`'s map (seeded `seed`) and hands each
/// pair of answers, the trial and its name to `check`.
template <typename Check>
void on_trials(const CoarseToFineEstimator& a, const CoarseToFineEstimator& b,
               const CorrelationEstimator& on, std::uint64_t seed, int trials, Check check) {
  Rng rng(seed);
  for (int trial = 0; trial < trials; ++trial) {
    const Trial t = trial_on(on, rng);
    check(a.estimate(t.observation, t.whole), b.estimate(t.observation, t.whole), t,
          "trial " + std::to_string(trial));
  }
}

/// Expects the same answer, bit for bit: pose, scores, hypotheses and verdict.
void expect_same_answer(const Estimate& a, const Estimate& b, const std::string& what) {
  EXPECT_EQ(a.pose.x, b.pose.x) << what;
  EXPECT_EQ(a.pose.y, b.pose.y) << what;
  EXPECT_EQ(a.pose.theta, b.pose.theta) << what;
  EXPECT_EQ(a.score, b.score) << what;
  EXPECT_EQ(a.second_score, b.second_score) << what;
  EXPECT_EQ(a.alternatives.size(), b.alternatives.size()) << what;
  EXPECT_EQ(a.verdict, b.verdict) << what;
}

double heading_gap(const Pose2& a, const Pose2& b) {
  return std::abs(normalize_angle(a.theta - b.theta));
}

// On the apartment (11 x 8 m at 5 cm), from no prior: the place the exact search of every
// pose finds, within a cell and two heading steps, and the truth within 10 cm and 2 deg.
TEST(CoarseToFine, FindsTheExactSearchsPlaceOnTheApartment) {
  const auto fine = laser_estimator("apartment_small");
  const CoarseToFineEstimator coarse_to_fine(fine);
  Rng rng(35);
  for (int trial = 0; trial < 6; ++trial) {
    const auto [truth, observation, whole] = trial_on(*fine, rng);
    const Estimate exact = fine->estimate(observation, whole);
    const Estimate fast = coarse_to_fine.estimate(observation, whole);
    const std::string what = "trial " + std::to_string(trial);
    EXPECT_LE(std::hypot(fast.pose.x - exact.pose.x, fast.pose.y - exact.pose.y), 0.05) << what;
    EXPECT_LE(heading_gap(fast.pose, exact.pose), 2.0 * whole.step_theta) << what;
    EXPECT_LE(std::hypot(fast.pose.x - truth.x, fast.pose.y - truth.y), 0.1) << what;
    EXPECT_LE(heading_gap(fast.pose, truth), 2.0 * std::numbers::pi / 180.0) << what;
    EXPECT_TRUE(exact.stats.proven_optimal) << what;
    EXPECT_FALSE(fast.stats.proven_optimal) << what;
    EXPECT_TRUE(std::isnan(fast.stats.upper_bound)) << what;
    EXPECT_EQ(fast.verdict, exact.verdict) << what;
    EXPECT_TRUE(fast.covariance.allFinite()) << what;
    EXPECT_GT(fast.covariance(0, 0), 0.0) << what;
  }
}

// In a room with a twin across its middle the search's places include both twins, and the
// verdict is ambiguous as the exact search's is.
TEST(CoarseToFine, ReportsTheTwinOfASymmetricRoom) {
  const auto fine = laser_estimator("room_symmetric");
  const CoarseToFineEstimator coarse_to_fine(fine);
  Rng rng(7);
  int ambiguous = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const auto [truth, observation, whole] = trial_on(*fine, rng);
    const Estimate exact = fine->estimate(observation, whole);
    const Estimate fast = coarse_to_fine.estimate(observation, whole);
    const std::string what = "trial " + std::to_string(trial);
    EXPECT_EQ(fast.verdict, exact.verdict) << what;
    EXPECT_EQ(fast.alternatives.size(), exact.alternatives.size()) << what;
    EXPECT_EQ(fast.second_below_floor, exact.second_below_floor) << what;
    ambiguous += fast.verdict == Verdict::Ambiguous ? 1 : 0;
  }
  EXPECT_GT(ambiguous, 0);  // the room's twins are found
}

// Without the second peak asked for, the places are the same (they are what the answer is
// chosen from): the same answer and hypotheses.
TEST(CoarseToFine, TheSecondPeakOptionLeavesThePlacesAlone) {
  const auto with = laser_estimator("apartment_small");
  const auto without = laser_estimator("apartment_small", false);
  const CoarseToFineEstimator a(with), b(without);
  on_trials(a, b, *with, 3, 3,
            [](const Estimate& ea, const Estimate& eb, const Trial&, const std::string& what) {
              expect_same_answer(ea, eb, what);
            });
}

// The fine estimator built for the refinement windows only (a shallow bound pyramid) gives
// the same answers as one deep enough for the whole map: every depth is exact.
TEST(CoarseToFine, AShallowFinePyramidGivesTheSameAnswers) {
  const CoarseToFineOptions options;
  const int depth = refinement_bound_depth(options, 0.05);
  EXPECT_EQ(depth, 5);  // 0.3 m = 6 cells each side: 13 cells, 2^4 >= 13, plus one
  const auto deep = laser_estimator("apartment_small");
  const auto shallow = laser_estimator("apartment_small", true, depth);
  const CoarseToFineEstimator a(deep, options), b(shallow, options);
  // The coarse copy searches the whole map whatever depth the fine estimator was built to.
  EXPECT_EQ(b.coarse().options().max_bound_depth, 0);
  Rng rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    const auto [truth, observation, whole] = trial_on(*deep, rng);
    const Estimate ea = a.estimate(observation, whole), eb = b.estimate(observation, whole);
    const std::string what = "trial " + std::to_string(trial);
    expect_same_answer(ea, eb, what);
    // A whole-map search on the shallow pyramid is still exact, only slower.
    const Estimate exact_deep = deep->estimate(observation, whole);
    const Estimate exact_shallow = shallow->estimate(observation, whole);
    EXPECT_EQ(exact_deep.lattice_pose.x, exact_shallow.lattice_pose.x) << what;
    EXPECT_EQ(exact_deep.lattice_pose.y, exact_shallow.lattice_pose.y) << what;
    EXPECT_EQ(exact_deep.score, exact_shallow.score) << what;
    EXPECT_TRUE(exact_shallow.stats.proven_optimal) << what;
  }
}

// A windowed search on a pyramid only as deep as its window needs (what `localize --prior`
// builds, issue 17) gives the same answer, bit for bit, as on one deep enough for the map.
TEST(CoarseToFine, AWindowsOwnPyramidDepthGivesTheSameWindowedAnswers) {
  SearchWindow half_metre;
  half_metre.half_xy = 0.5;
  half_metre.step_xy = 0.05;
  EXPECT_EQ(window_bound_depth(half_metre), 6);  // 21 cells: 2^5 >= 21, plus one
  const auto deep = laser_estimator("apartment_small");
  Rng rng(23);
  for (int trial = 0; trial < 6; ++trial) {
    const auto [truth, observation, whole] = trial_on(*deep, rng);
    SearchWindow window = half_metre;
    window.half_xy = 0.3 + 0.35 * trial;  // 0.3 to 2.05 m
    window.half_theta = 0.3;
    window.step_theta = 0.02;
    window.center = {truth.x + 0.1, truth.y - 0.1, truth.theta + 0.05};
    const int depth = window_bound_depth(window);
    const auto shallow = laser_estimator("apartment_small", true, depth);
    const std::string what = "trial " + std::to_string(trial) + ", depth " + std::to_string(depth);
    const Estimate a = deep->estimate(observation, window);
    const Estimate b = shallow->estimate(observation, window);
    expect_same_answer(a, b, what);
    EXPECT_TRUE(b.stats.proven_optimal) << what;
    EXPECT_EQ(a.stats.poses_scored, b.stats.poses_scored) << what;  // the same search
  }
}

// The answer is ambiguous exactly when a far refined place scores ambiguity_ratio of the best.
TEST(CoarseToFine, AFarPlaceAtTheAmbiguityRatioMakesTheAnswerAmbiguous) {
  const auto fine = laser_estimator("apartment_small");
  const CoarseToFineEstimator first(fine);
  Rng rng(21);
  bool tried = false;
  for (int trial = 0; trial < 20 && !tried; ++trial) {
    const Pose2 truth = sample_free_pose(fine->map(), SonarRing{}, 0.4, rng);
    Observation observation;
    observation.scan = simulate_scan(fine->map(), truth, 90, 2.0, 0.01, rng.next());  // short
    const SearchWindow whole = fine->global_window(observation);
    const Estimate e = first.estimate(observation, whole);
    if (e.alternatives.size() < 2) continue;
    const Hypothesis& second = e.alternatives[1];
    const double far =
        std::hypot(second.pose.x - e.lattice_pose.x, second.pose.y - e.lattice_pose.y);
    if (far <= 1.0 || e.verdict == Verdict::NotLocalized) continue;
    const double ratio = second.score / e.score;
    CoarseToFineOptions options;
    options.ambiguity_ratio = ratio - 0.005;
    EXPECT_EQ(CoarseToFineEstimator(fine, options).estimate(observation, whole).verdict,
              Verdict::Ambiguous);
    options.ambiguity_ratio = std::min(1.0, ratio + 0.005);
    const Estimate above = CoarseToFineEstimator(fine, options).estimate(observation, whole);
    if (ratio + 0.005 <= 1.0) {
      EXPECT_NE(above.verdict, Verdict::Ambiguous);
    }
    tried = true;
  }
  EXPECT_TRUE(tried) << "no trial with a far second place";
}

/// A square of `cells` cells of 5 cm with an L of walls on row and column `wall`, open to the
/// right and the top, and a bar on row `bar_row` from column `bar_begin` to `bar_end`.
OccupancyMap open_l_room(int cells, int wall, int bar_row, int bar_begin, int bar_end) {
  GridGeometry geometry;
  geometry.resolution = 0.05;
  geometry.width = geometry.height = cells;
  OccupancyMap map(geometry, CellState::Free);
  for (int i = 0; i < cells; ++i) map.at(wall, i) = map.at(i, wall) = CellState::Occupied;
  for (int i = bar_begin; i < bar_end; ++i) map.at(i, bar_row) = CellState::Occupied;
  return map;
}

/// The coarse-to-fine answer to a noise-free scan of `map` from `truth`, at `coarse` m cells.
Estimate small_map_answer(const OccupancyMap& map, const Pose2& truth, double reach,
                          double coarse) {
  CorrelationOptions correlation;
  correlation.global = GlobalModel::LikelihoodField;
  correlation.resolution = 0.05;
  correlation.reach_m = reach;
  const auto fine = std::make_shared<const CorrelationEstimator>(map, correlation);
  CoarseToFineOptions options;
  options.resolution = coarse;
  Observation observation;
  observation.scan = simulate_scan(map, truth, 180, reach, 0.0, 1);
  return CoarseToFineEstimator(fine, options)
      .estimate(observation, fine->global_window(observation));
}

// A map whose width is no whole number of coarse cells: the last coarse cell overhangs it, and
// a place found there is refined inside the map (not refused as a window outside it). 1.5 m
// wide (7.5 coarse cells of 0.2 m), the robot 5 cm from the right edge.
TEST(CoarseToFine, APlaceInTheCoarseCellOverhangingTheMapIsRefinedInside) {
  const Pose2 truth{1.44, 0.33, 3.0};
  const Estimate e = small_map_answer(open_l_room(30, 2, 14, 10, 20), truth, 3.0, 0.2);
  EXPECT_LE(std::hypot(e.pose.x - truth.x, e.pose.y - truth.y), 0.1);
}

// A map narrower than a refinement window (1 m, 0.5 m coarse cells: windows of +-0.75 m):
// the windows span at most the whole map, not an error about a window larger than it.
TEST(CoarseToFine, AMapNarrowerThanAWindowIsSearchedWhole) {
  const Pose2 truth{0.62, 0.38, 2.5};
  const Estimate e = small_map_answer(open_l_room(20, 1, 12, 8, 14), truth, 2.0, 0.5);
  EXPECT_LE(std::hypot(e.pose.x - truth.x, e.pose.y - truth.y), 0.1);
}

// A scan that sees through a wall of the map is not localized: the apartment with a ring of
// wall 0.5 m around the truth that the scan (simulated without it) does not see. Every
// return beyond the ring crosses it; without the check the answer is the truth, localized.
TEST(CoarseToFine, AScanSeeingThroughTheMapsWallsIsNotLocalized) {
  const auto plain = laser_estimator("apartment_small");
  Rng rng(11);
  Trial t = trial_on(*plain, rng);
  const auto clear = [&](const Pose2& p) {
    for (double dy = -0.6; dy <= 0.6; dy += 0.05) {
      for (double dx = -0.6; dx <= 0.6; dx += 0.05) {
        const Pose2 local = plain->map().geometry.to_grid_frame({p.x + dx, p.y + dy, 0.0});
        const Cell c = plain->map().geometry.cell_of(local.x, local.y);
        if (plain->map().at(c.ix, c.iy) != CellState::Free) return false;
      }
    }
    return true;
  };
  while (!clear(t.truth)) t = trial_on(*plain, rng);
  OccupancyMap ringed = plain->map();
  for (int k = 0; k < 360; ++k) {
    const double a = k * std::numbers::pi / 180.0;
    const Pose2 local = ringed.geometry.to_grid_frame(
        {t.truth.x + 0.5 * std::cos(a), t.truth.y + 0.5 * std::sin(a), 0.0});
    const Cell c = ringed.geometry.cell_of(local.x, local.y);
    ringed.at(c.ix, c.iy) = CellState::Occupied;
  }
  const auto fine = std::make_shared<const CorrelationEstimator>(ringed, plain->options());
  CoarseToFineOptions unchecked;
  unchecked.through_wall_ratio = 0.0;
  const Estimate trusting = CoarseToFineEstimator(fine, unchecked).estimate(t.observation, t.whole);
  ASSERT_LE(std::hypot(trusting.pose.x - t.truth.x, trusting.pose.y - t.truth.y), 0.1);
  ASSERT_EQ(trusting.verdict, Verdict::Localized);
  EXPECT_TRUE(std::isnan(trusting.through_walls));
  const Estimate checked = CoarseToFineEstimator(fine).estimate(t.observation, t.whole);
  EXPECT_GT(checked.through_walls, 0.7 * checked.normalized_score);
  EXPECT_EQ(checked.verdict, Verdict::NotLocalized);
  // On the map as the scan saw it, the same check passes.
  const Estimate seen = CoarseToFineEstimator(plain).estimate(t.observation, t.whole);
  EXPECT_EQ(seen.verdict, Verdict::Localized);
  EXPECT_LT(seen.through_walls, 0.05);
}

// The reported floor (a real map's error) widens the answer's covariance by its squares on
// the diagonal and changes nothing else.
TEST(CoarseToFine, TheReportedFloorWidensOnlyTheCovariance) {
  const auto fine = laser_estimator("apartment_small");
  CoarseToFineOptions bare;
  bare.reported_floor_m = 0.0;
  bare.reported_floor_rad = 0.0;
  const CoarseToFineOptions floored;
  const CoarseToFineEstimator a(fine, floored), b(fine, bare);
  const Eigen::Vector3d floor(0.03 * 0.03, 0.03 * 0.03, std::pow(0.5 * std::numbers::pi / 180, 2));
  on_trials(a, b, *fine, 19, 2,
            [&](const Estimate& ea, const Estimate& eb, const Trial&, const std::string& what) {
              expect_same_answer(ea, eb, what);
              EXPECT_EQ(ea.confidence, eb.confidence) << what;
              const Eigen::Matrix3d added = ea.covariance - eb.covariance;
              EXPECT_NEAR((added - Eigen::Matrix3d(floor.asDiagonal())).norm(), 0.0, 1e-12) << what;
            });
}

TEST(CoarseToFine, BadOptionsAreRefused) {
  const auto fine = laser_estimator("room_rect");
  CoarseToFineOptions options;
  options.resolution = 0.05;  // the fine cell itself
  test::expect_error([&] { CoarseToFineEstimator(fine, options); },
                     {"resolution", "coarser than the fine cell"});
  options.resolution = 0.6;  // ranks places too poorly
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"resolution", "0.5 m"});
  options = {};
  options.places = 0;
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"places", "[1, 100]"});
  options.places = 101;  // more hypotheses than a search reports
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"places", "[1, 100]"});
  options = {};
  options.ambiguity_ratio = 1.5;
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"ambiguity_ratio"});
  options = {};
  options.ridge_ratio = 0.0;
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"ridge_ratio"});
  options = {};
  options.half_xy_cells = std::nan("");
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"half_xy_cells"});
  options = {};
  options.through_wall_ratio = -0.1;
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"through_wall_ratio"});
  options = {};
  options.through_wall_margin_m = std::nan("");
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"through_wall_margin_m"});
  options = {};
  options.reported_floor_m = -0.01;
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"reported_floor_m", "-0.01"});
  options = {};
  options.reported_floor_rad = std::nan("");
  test::expect_error([&] { CoarseToFineEstimator(fine, options); }, {"reported_floor_rad"});
  test::expect_error([&] { CoarseToFineEstimator(nullptr, {}); }, {"no fine estimator"});
  CorrelationOptions too_deep = fine->options();
  too_deep.max_bound_depth = 40;
  test::expect_error([&] { CorrelationEstimator(fine->map(), too_deep); }, {"max_bound_depth"});
}

}  // namespace
}  // namespace gridloc
