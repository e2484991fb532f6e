// Ties over headings (issue 13): integer scan scores often tie over a run of headings at the
// winner's cell; refinement starts from the middle of that run, not from the search's
// lowest-index winner at its start.
#include <gtest/gtest.h>

#include <cmath>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

TEST(HeadingTies, RefinementStartsFromTheMiddleOfTiedHeadings) {
  // One return 1 cm from the sensor lands in the robot's own cell at every heading: every
  // heading of the window ties, and the search's winner is its first (-45 deg).
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  CorrelationOptions options;
  options.resolution = 0.05;
  options.reach_m = 8.0;
  const CorrelationEstimator estimator(map, options);
  RangeScan scan;
  scan.angles = {0.0};
  scan.ranges = {0.01};
  SearchWindow window;
  window.center = {0.5, 0.5, 0.0};
  window.step_xy = 0.05;
  const Estimate e = estimator.estimate(Observation{{}, scan}, window);
  EXPECT_NEAR(e.lattice_pose.theta, -window.half_theta, 1e-9);  // ties to the lowest index
  // The run is searched up to 8 steps each way: the middle of its first 9 headings.
  EXPECT_NEAR(e.pose.theta, -window.half_theta + 4 * window.step_theta, 1e-9);
}

}  // namespace
}  // namespace gridloc
