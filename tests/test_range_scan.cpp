// Tests of sensors/src/range_scan.cpp: the laser/IR scan model, its validation and CSV input,
// and localization of the shared peer-comparison scans (skipped when ../shared is absent).
#include "gridloc/sensors/range_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "gridloc/engine/correlation_estimator.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kRes = 0.1;

double sum_of(const SparseLocalGrid& g, bool positive) {
  double s = 0.0;
  for (float v : g.value) s += (v > 0.0f) == positive ? v : 0.0f;
  return s;
}

TEST(RangeScan, OneBeamHasAnEndCellAndMinusOneBeforeIt) {
  for (double angle : {0.0, 0.4, 1.9, -2.7}) {
    const RangeScan scan{{angle}, {3.0}, 8.0};
    const SparseLocalGrid g = rasterize_scan(scan, 0.25, kRes);
    EXPECT_DOUBLE_EQ(sum_of(g, true), 1.0) << angle;
    EXPECT_NEAR(sum_of(g, false), -1.0, 1e-5) << angle;
    // The end cell is where the beam ends.
    const double a = 0.25 + angle;
    const int ex = static_cast<int>(std::floor(3.0 * std::cos(a) / kRes + 0.5));
    const int ey = static_cast<int>(std::floor(3.0 * std::sin(a) / kRes + 0.5));
    bool found = false;
    for (std::size_t k = 0; k < g.size(); ++k) {
      if (g.value[k] > 0.0f) found = g.dx[k] == ex && g.dy[k] == ey;
    }
    EXPECT_TRUE(found) << angle;
  }
}

TEST(RangeScan, NoReturnGivesFreeSpaceToMaxRange) {
  const RangeScan scan{{0.0, 1.0}, {8.0, 2.0}, 8.0};
  const SparseLocalGrid g = rasterize_scan(scan, 0.0, kRes, {}, {ScanModel::Rays});
  EXPECT_DOUBLE_EQ(sum_of(g, true), 1.0);  // only the second beam hits
  EXPECT_GE(g.extent(), 79);               // the first beam's free cells reach 8 m
  // Samples: the last of 4 lies at 7/8 of the range.
  const SparseLocalGrid s = rasterize_scan(scan, 0.0, kRes, {}, {ScanModel::Samples, 4});
  EXPECT_EQ(s.extent(), 70);
  EXPECT_NEAR(sum_of(s, false), -2.0, 1e-6);
}

TEST(RangeScan, ACellHitByTwoBeamsStaysPlusOne) {
  const RangeScan scan{{0.0, 0.001}, {2.0, 2.0}, 8.0};
  const SparseLocalGrid g = rasterize_scan(scan, 0.0, kRes);
  EXPECT_DOUBLE_EQ(sum_of(g, true), 1.0);
}

TEST(RangeScan, CellsAreSortedByRowThenColumn) {
  RangeScan scan;
  for (int k = 0; k < 90; ++k) {
    scan.angles.push_back(k * 2.0 * std::numbers::pi / 90);
    scan.ranges.push_back(1.0 + 0.03 * k);
  }
  const SparseLocalGrid g = rasterize_scan(scan, 0.3, kRes);
  for (std::size_t k = 1; k < g.size(); ++k) {
    EXPECT_TRUE(std::pair(g.dy[k - 1], g.dx[k - 1]) < std::pair(g.dy[k], g.dx[k])) << k;
  }
}

TEST(RangeScanErrors, BadScansAreNamed) {
  test::expect_error([] { validate(RangeScan{{}, {}, 8.0}); }, {"no beams"});
  test::expect_error([] { validate(RangeScan{{0.0, 1.0}, {2.0}, 8.0}); }, {"angles", "ranges"});
  test::expect_error([] { validate(RangeScan{{NAN}, {2.0}, 8.0}); }, {"angle", "beam 0"});
  test::expect_error([] { validate(RangeScan{{0.0}, {-1.0}, 8.0}); }, {"negative", "beam 0"});
  test::expect_error([] { validate(RangeScan{{0.0}, {NAN}, 8.0}); }, {"NaN"});
  test::expect_error([] { validate(RangeScan{{0.0, 1.0}, {8.0, 9.0}, 8.0}); }, {"no beam"});
  test::expect_error([] { validate(RangeScan{{0.0}, {1.0}, 0.0}); }, {"max range"});
}

TEST(RangeScanErrors, CsvInput) {
  test::TempDir dir;
  const auto good = dir.path() / "good.csv";
  std::ofstream(good) << "# angle_rad,range_m\n\n0.0,1.5\n 0.5 , 9.0  # no return\n";
  const RangeScan scan = load_scan_csv(good.string(), 8.0);
  ASSERT_EQ(scan.ranges.size(), 2u);
  EXPECT_DOUBLE_EQ(scan.angles[1], 0.5);
  EXPECT_DOUBLE_EQ(scan.ranges[1], 9.0);

  const auto bad = dir.path() / "bad.csv";
  std::ofstream(bad) << "0.0,1.5\n0.1;x\n";
  test::expect_error([&] { load_scan_csv(bad.string(), 8.0); }, {"bad.csv:2", "angle_rad"});
  test::expect_error([&] { load_scan_csv((dir.path() / "none.csv").string(), 8.0); },
                     {"none.csv", "not found"});
  const auto empty = dir.path() / "empty.csv";
  std::ofstream(empty) << "# nothing\n";
  test::expect_error([&] { load_scan_csv(empty.string(), 8.0); }, {"empty.csv", "no beams"});
}

TEST(RangeScanEstimator, ScanBeyondTheEstimatorsReachIsAnError) {
  const OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  CorrelationOptions o;
  o.reach_m = 4.0;
  const CorrelationEstimator estimator(map, o);
  Observation obs;
  obs.scan = RangeScan{{0.0}, {2.0}, 8.0};
  SearchWindow w;
  w.center = {2.0, 2.0, 0.0};
  test::expect_error([&] { (void)estimator.estimate(obs, w); }, {"reach"});
  obs.scan->max_range = 4.0;
  obs.ranges = {1.0};
  test::expect_error([&] { (void)estimator.estimate(obs, w); }, {"not both"});
  test::expect_error([&] { (void)estimator.estimate(Observation{{1.0}}, w); }, {"no sonar ring"});
}

/// The peer-comparison case of ../shared/bench-cases/apartment: two 360-beam scans, windowed
/// search from the README's start poses.
TEST(RangeScanEstimator, SharedApartmentCases) {
  const std::filesystem::path dir =
      std::filesystem::path(GRIDLOC_TEST_SHARED_DIR) / "bench-cases" / "apartment";
  if (!std::filesystem::exists(dir / "apartment.yaml")) {
    GTEST_SKIP() << "shared bench case not found at " << dir << " (../shared is absent)";
  }
  CorrelationOptions o;
  o.resolution = 0.05;
  o.reach_m = 8.0;
  const CorrelationEstimator estimator(load_ros_map((dir / "apartment.yaml").string()), o);
  struct Case {
    const char* scan;
    Pose2 start, truth;
  };
  for (const Case& c : {Case{"scan.csv", {2.53, -0.07, 0.70}, {2.30, 0.10, 0.600}},
                        Case{"case2/scan.csv", {9.06, 8.34, -2.25}, {9.37, 8.12, -2.100}}}) {
    Observation obs;
    obs.scan = load_scan_csv((dir / c.scan).string(), 8.0);
    SearchWindow w{c.start, 0.5, 0.3, 0.05, 0.005};
    const Estimate e = estimator.estimate(obs, w);
    EXPECT_LE(std::hypot(e.pose.x - c.truth.x, e.pose.y - c.truth.y), 0.03) << c.scan;
    EXPECT_LE(std::abs(normalize_angle(e.pose.theta - c.truth.theta)), deg2rad(0.5)) << c.scan;
  }
}

}  // namespace
}  // namespace gridloc
