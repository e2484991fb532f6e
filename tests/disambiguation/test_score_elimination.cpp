#include "gridloc/engine/disambiguation/score_elimination.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {
namespace {

TEST(WithinDropRatio, KeepsTheScoresNearTheBest) {
  EXPECT_EQ(within_drop_ratio({100.0, 96.0, 98.0, 80.0}, 0.97), (std::vector<int>{0, 2}));
  EXPECT_EQ(within_drop_ratio({100.0, 96.0, 98.0, 80.0}, 0.8), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(within_drop_ratio({-3.0, -1.0, -1.0}, 0.9), (std::vector<int>{1, 2}));  // best <= 0
  EXPECT_TRUE(within_drop_ratio({}, 0.9).empty());
  EXPECT_THROW(within_drop_ratio({1.0}, 0.0), Error);
  EXPECT_THROW(within_drop_ratio({1.0}, std::nan("")), Error);
}

TEST(ScorePredictions, TheTruePlaceOutscoresAWrongOneAndWindowsGrowWithTheDrive) {
  const OccupancyMap map =
      load_ros_map(std::string(GRIDLOC_TEST_MAPS_DIR) + "/room_furnished.yaml");
  const SonarRing ring =
      load_sonar_ring(std::string(GRIDLOC_TEST_MAPS_DIR) + "/sensors/wheelchair_14.yaml");
  const CorrelationEstimator estimator(map, ring);
  const Pose2 truth{2.0, 2.5, 0.3};
  Observation observation;
  observation.ranges = simulate_sonar(map, ring, truth, SonarSimOptions::realistic(3));
  const std::vector<Estimate> estimates =
      score_predictions(estimator, observation, {{2.1, 2.45, 0.35}, {4.5, 3.5, -1.0}}, 0.0, {});
  ASSERT_EQ(estimates.size(), 2u);
  EXPECT_GT(estimates[0].score, estimates[1].score);
  EXPECT_LT(std::hypot(estimates[0].pose.x - truth.x, estimates[0].pose.y - truth.y), 0.2);
  EXPECT_EQ(within_drop_ratio({estimates[0].score, estimates[1].score}, 0.97), std::vector<int>{0});
  const ScoreEliminationOptions options;
  const SearchWindow still = prediction_window(estimator, observation, truth, 0.0, options);
  const SearchWindow driven = prediction_window(estimator, observation, truth, 5.0, options);
  EXPECT_DOUBLE_EQ(still.half_xy, options.half_xy);
  EXPECT_GT(driven.half_xy, still.half_xy);
  EXPECT_GT(driven.half_theta, still.half_theta);
  EXPECT_THROW(score_predictions(estimator, observation, {truth}, -1.0, options), Error);
}

}  // namespace
}  // namespace gridloc
