// Tests of the overlap of two scans and the failure table by overlap band
// (engine/src/evaluation/scan_overlap.cpp, issue 30).
#include <gtest/gtest.h>

#include <vector>

#include "gridloc/engine/evaluation/scan_overlap.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

/// Points every 5 cm along y = 0 from x = `from` to x = `to`.
std::vector<Eigen::Vector2d> wall(double from, double to) {
  std::vector<Eigen::Vector2d> points;
  for (double x = from; x <= to + 1e-9; x += 0.05) points.emplace_back(x, 0.0);
  return points;
}

TEST(ScanOverlap, AScanOverlapsItselfWhole) {
  const auto points = wall(0.0, 5.0);
  EXPECT_EQ(scan_overlap(points, points, {0.0, 0.0, 0.0}), 1.0);
}

TEST(ScanOverlap, CountsTheReturnsWithinTheRadiusAtTheMotion) {
  const auto reference = wall(0.0, 5.0);
  EXPECT_EQ(scan_overlap(reference, reference, {0.0, 0.1, 0.0}), 1.0);  // 10 cm off the wall
  EXPECT_EQ(scan_overlap(reference, reference, {0.0, 0.3, 0.0}), 0.0);  // 30 cm off
  EXPECT_EQ(scan_overlap(reference, reference, {0.0, 0.3, 0.0}, 0.35), 1.0);
  // The current wall runs on 5 m past the reference's end: half of it overlaps.
  const auto longer = wall(0.0, 10.0);
  EXPECT_NEAR(scan_overlap(reference, longer, {0.0, 0.0, 0.0}), 105.0 / 201.0, 1e-12);
}

TEST(ScanOverlap, TheMotionTurnsTheCurrentScan) {
  // A wall along x, seen from a frame turned by 90 degrees (where it runs along -y).
  const auto reference = wall(1.0, 3.0);
  std::vector<Eigen::Vector2d> turned;
  for (const auto& p : reference) turned.emplace_back(0.0, -p.x());
  EXPECT_EQ(scan_overlap(reference, turned, {0.0, 0.0, 0.5 * 3.14159265358979}), 1.0);
  EXPECT_EQ(scan_overlap(reference, turned, {0.0, 0.0, 0.0}), 0.0);
}

TEST(ScanOverlap, AnEmptyScanOverlapsNothing) {
  EXPECT_EQ(scan_overlap(wall(0, 1), {}, {0.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(scan_overlap({}, wall(0, 1), {0.0, 0.0, 0.0}), 0.0);
}

TEST(FailuresByBand, CountsEachOverlapInItsBand) {
  const std::vector<double> overlaps = {0.0, 0.19, 0.2, 0.5, 0.79, 0.8, 1.0, 1.0};
  const std::vector<bool> failed = {true, true, false, true, false, false, true, false};
  const auto rows = failures_by_band(overlaps, failed, {0.2, 0.4, 0.6, 0.8});
  ASSERT_EQ(rows.size(), 5u);
  const std::vector<std::string> labels = {"0-0.2", "0.2-0.4", "0.4-0.6", "0.6-0.8", "0.8-1"};
  const std::vector<int> pairs = {2, 1, 1, 1, 3}, failures = {2, 0, 1, 0, 1};
  for (std::size_t b = 0; b < rows.size(); ++b) {
    EXPECT_EQ(rows[b].label, labels[b]);
    EXPECT_EQ(rows[b].pairs, pairs[b]) << b;
    EXPECT_EQ(rows[b].failures, failures[b]) << b;
  }
}

TEST(FailuresByBand, BadEdgesAndSizesAreNamed) {
  test::expect_error(
      [] {
        failures_by_band({0.5}, {true}, {0.6, 0.4});
      },
      {"overlap bands", "0.4 after 0.6"});
  test::expect_error([] { failures_by_band({0.5}, {true}, {1.0}); }, {"inside (0, 1)"});
  test::expect_error(
      [] {
        failures_by_band({0.5, 0.6}, {true}, {0.5});
      },
      {"2 overlaps but 1 outcomes"});
  EXPECT_EQ(failures_by_band({}, {}, {}).size(), 1u);  // one band: 0-1
}

}  // namespace
}  // namespace gridloc
