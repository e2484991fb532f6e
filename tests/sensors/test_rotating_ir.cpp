// Tests of sensors/src/rotating_ir.cpp: the rotating IR sensor of seed 003 ch. VI (its
// simulator on polygon and occupancy maps, the Table II noise, the moving-average filter, the
// CSV reader and the options' checks).
#include "gridloc/sensors/rotating_ir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;
using test::TempDir;

/// The 1 m square room [0, 1] x [0, 1].
PolygonMap unit_square() {
  return make_polygon_map({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {});
}

/// Noise-free, unsmoothed options with `readings` readings per turn.
IrSensorOptions exact_options(int readings = 360) {
  IrSensorOptions o;
  o.readings = readings;
  o.noise = false;
  o.smoothing_half_window = 0;
  return o;
}

// With 360 readings from -pi: reading 0 looks along -x, 90 along -y, 180 along +x, 270 along +y.
constexpr int kMinusX = 0, kMinusY = 90, kPlusX = 180;

TEST(SimulateIrScan, PolygonScanReadsTheWallDistances) {
  const Pose2 pose{0.2, 0.3, 0.0};
  const RangeScan s = simulate_ir_scan(unit_square(), pose, exact_options(), 1);
  ASSERT_EQ(s.ranges.size(), 360u);
  ASSERT_EQ(s.angles.size(), 360u);
  EXPECT_EQ(s.max_range, 0.30);
  EXPECT_NEAR(s.ranges[kMinusX], 0.2, 1e-9);
  EXPECT_EQ(s.ranges[kPlusX], 0.30);  // the wall 0.8 m away: saturated, exactly max
  for (int k = 0; k < 360; ++k) {
    EXPECT_DOUBLE_EQ(s.angles[k], -std::numbers::pi + 2.0 * std::numbers::pi * k / 360);
  }
  // The wall 0.3 m away is at the default truncation range: read it with a longer one.
  IrSensorOptions longer = exact_options();
  longer.max_range_m = 0.5;
  const RangeScan l = simulate_ir_scan(unit_square(), pose, longer, 1);
  EXPECT_NEAR(l.ranges[kMinusY], 0.3, 1e-9);
  EXPECT_NEAR(l.ranges[kMinusX], 0.2, 1e-9);
  EXPECT_EQ(l.ranges[kPlusX], 0.5);
}

TEST(SimulateIrScan, HeadingTurnsTheScan) {
  // Facing +y, reading 90 (robot -y) looks along world +x.
  IrSensorOptions o = exact_options();
  o.max_range_m = 0.9;
  const RangeScan s = simulate_ir_scan(unit_square(), {0.2, 0.3, std::numbers::pi / 2}, o, 1);
  EXPECT_NEAR(s.ranges[kMinusY], 0.8, 1e-9);
  EXPECT_NEAR(s.ranges[kMinusX], 0.3, 1e-9);  // robot -x is world -y
}

TEST(SimulateIrScan, CloseWallsReadTheMinimumRange) {
  const RangeScan s = simulate_ir_scan(unit_square(), {0.05, 0.5, 0.0}, exact_options(), 1);
  EXPECT_EQ(s.ranges[kMinusX], 0.09);
}

/// Distance (m) of world point (x, y) from the nearest wall of the unit square.
double wall_distance(double x, double y) {
  return std::min({x, 1.0 - x, y, 1.0 - y});
}

TEST(SimulateIrScan, OccupancyScanAgreesWithThePolygonScanWithinACell) {
  // The grid's walls are the cells the edges cross, a cell thick inside the room or outside
  // it: every grid beam ends no farther than the exact one and within a cell of a wall (along
  // a slanted beam the range difference itself grows as 1 / cos of the incidence). A range
  // beyond the room's diagonal makes every reading a return.
  const PolygonMap polygon = unit_square();
  constexpr double kRes = 0.02;
  const OccupancyMap grid = rasterize_polygon_map(polygon, kRes);
  IrSensorOptions o = exact_options();
  o.max_range_m = 1.5;
  for (const Pose2& pose : {Pose2{0.2, 0.3, 0.0}, Pose2{0.71, 0.44, 0.7}}) {
    const RangeScan exact = simulate_ir_scan(polygon, pose, o, 1);
    const RangeScan cells = simulate_ir_scan(grid, pose, o, 1);
    ASSERT_EQ(cells.ranges.size(), exact.ranges.size());
    EXPECT_EQ(cells.angles, exact.angles);
    EXPECT_EQ(cells.max_range, 1.5);
    for (std::size_t k = 0; k < exact.ranges.size(); ++k) {
      const double a = pose.theta + exact.angles[k], r = cells.ranges[k];
      ASSERT_LT(exact.ranges[k], 1.5);
      EXPECT_NEAR(wall_distance(pose.x + exact.ranges[k] * std::cos(a),
                                pose.y + exact.ranges[k] * std::sin(a)),
                  0.0, 1e-9);
      EXPECT_LE(r, exact.ranges[k] + 1e-9) << "reading " << k;
      EXPECT_LE(wall_distance(pose.x + r * std::cos(a), pose.y + r * std::sin(a)), kRes + 1e-9)
          << "reading " << k;
    }
  }
}

TEST(SimulateIrScan, NoiseIsSeededAndLeavesSaturationAlone) {
  IrSensorOptions o;
  o.smoothing_half_window = 0;
  const Pose2 pose{0.2, 0.3, 0.0};
  const RangeScan a = simulate_ir_scan(unit_square(), pose, o, 7);
  const RangeScan b = simulate_ir_scan(unit_square(), pose, o, 7);
  const RangeScan c = simulate_ir_scan(unit_square(), pose, o, 8);
  EXPECT_EQ(a.ranges, b.ranges);
  EXPECT_NE(a.ranges, c.ranges);
  EXPECT_EQ(a.ranges[kPlusX], 0.30);
  EXPECT_NE(a.ranges[kMinusX], 0.2);
  EXPECT_NEAR(a.ranges[kMinusX], 0.2, 5 * ir_range_sigma(0.2));
  for (double r : a.ranges) {
    EXPECT_TRUE(r == 0.30 || (r >= 0.09 && r <= 0.30 - 1e-6)) << r;
  }
}

TEST(SimulateIrScan, NoiseHasTheTableSpread) {
  // 2000 scans of 8 readings from (0.5, 0.2): reading 2 (-pi/2) sees the wall at 0.2 m.
  IrSensorOptions o;
  o.readings = 8;
  o.smoothing_half_window = 0;
  constexpr int kScans = 2000;
  double sum = 0.0, sum2 = 0.0;
  for (int seed = 1; seed <= kScans; ++seed) {
    const double r = simulate_ir_scan(unit_square(), {0.5, 0.2, 0.0}, o, seed).ranges[2];
    sum += r;
    sum2 += r * r;
  }
  const double mean = sum / kScans;
  const double std = std::sqrt((sum2 - kScans * mean * mean) / (kScans - 1));
  const double sigma = ir_range_sigma(0.2);
  EXPECT_NEAR(std, sigma, 0.1 * sigma);
  EXPECT_NEAR(mean, 0.2, 4 * sigma / std::sqrt(kScans));
}

TEST(SimulateIrScan, SmoothsWithTheOptionsWindow) {
  IrSensorOptions o;
  o.smoothing_half_window = 3;
  const Pose2 pose{0.2, 0.3, 0.0};
  IrSensorOptions raw = o;
  raw.smoothing_half_window = 0;
  const RangeScan smoothed = simulate_ir_scan(unit_square(), pose, o, 3);
  const RangeScan expected = smooth_ir_scan(simulate_ir_scan(unit_square(), pose, raw, 3), 3);
  EXPECT_EQ(smoothed.ranges, expected.ranges);
}

TEST(SimulateIrScan, RefusesBadOptionsAndPoses) {
  IrSensorOptions o;
  o.readings = 4;
  expect_error([&] { simulate_ir_scan(unit_square(), {0.5, 0.5, 0.0}, o, 1); }, {"readings"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_error(
      [&] {
        simulate_ir_scan(unit_square(), {nan, 0.5, 0.0}, IrSensorOptions{}, 1);
      },
      {"simulate_ir_scan", "pose"});
  const OccupancyMap grid = rasterize_polygon_map(unit_square());
  expect_error([&] { simulate_ir_scan(grid, {0.5, 0.5, nan}, IrSensorOptions{}, 1); }, {"pose"});
}

TEST(IrRangeSigma, FollowsTableII) {
  EXPECT_NEAR(ir_range_sigma(0.1141), 0.0042 / 3.92, 1e-12);
  EXPECT_NEAR(ir_range_sigma(0.2252), 0.0125 / 3.92, 1e-12);
  EXPECT_NEAR(ir_range_sigma(0.3000), 0.0221 / 3.92, 1e-12);
  EXPECT_NEAR(ir_range_sigma(0.3982), 0.0683 / 3.92, 1e-12);
  // Constant below the first range.
  EXPECT_EQ(ir_range_sigma(0.05), ir_range_sigma(0.0));
  EXPECT_NEAR(ir_range_sigma(0.05), 0.0042 / 3.92, 1e-12);
  // Linear between: 17 cm is (17 - 11.41) / 11.11 of the way from 0.42 to 1.25 cm.
  EXPECT_NEAR(ir_range_sigma(0.17), (0.42 + 5.59 / 11.11 * 0.83) / 392.0, 1e-12);
  // The last slope, (6.83 - 2.21) / 9.82 cm per cm, continued beyond 39.82 cm.
  EXPECT_NEAR(ir_range_sigma(0.50), (6.83 + 10.18 * 4.62 / 9.82) / 392.0, 1e-12);
  expect_error([] { ir_range_sigma(std::numeric_limits<double>::quiet_NaN()); }, {"NaN"});
}

/// Eight readings 45 degrees apart, max range 0.3; reading 2 saturated.
/// Eight readings round the turn, reading 2 saturated, no jump over 5 cm between neighbours
/// (also across the wrap from reading 7 to 0).
RangeScan hand_scan() {
  RangeScan s;
  s.max_range = 0.3;
  s.ranges = {0.10, 0.12, 0.30, 0.14, 0.16, 0.18, 0.16, 0.12};
  for (int k = 0; k < 8; ++k) s.angles.push_back(-std::numbers::pi + k * std::numbers::pi / 4);
  return s;
}

TEST(SmoothIrScan, AveragesSymmetricallyAroundTheTurn) {
  const RangeScan in = hand_scan();
  const RangeScan out = smooth_ir_scan(in, 1);
  EXPECT_EQ(out.angles, in.angles);
  EXPECT_EQ(out.max_range, 0.3);
  ASSERT_EQ(out.ranges.size(), 8u);
  EXPECT_NEAR(out.ranges[0], (0.12 + 0.10 + 0.12) / 3, 1e-12);  // wraps to reading 7
  EXPECT_EQ(out.ranges[1], 0.12);  // next to the saturated reading: no symmetric window
  EXPECT_EQ(out.ranges[2], 0.30);  // saturated stays
  EXPECT_EQ(out.ranges[3], 0.14);
  EXPECT_NEAR(out.ranges[4], (0.14 + 0.16 + 0.18) / 3, 1e-12);
  EXPECT_NEAR(out.ranges[5], (0.16 + 0.18 + 0.16) / 3, 1e-12);
  EXPECT_NEAR(out.ranges[6], (0.18 + 0.16 + 0.12) / 3, 1e-12);
  EXPECT_NEAR(out.ranges[7], (0.16 + 0.12 + 0.10) / 3, 1e-12);  // wraps to reading 0
}

TEST(SmoothIrScan, TheWindowShrinksAlikeOnBothSidesNearTheWallsEnd) {
  const RangeScan two = smooth_ir_scan(hand_scan(), 2);
  EXPECT_NEAR(two.ranges[0], (0.12 + 0.10 + 0.12) / 3, 1e-12);  // reading 2 one beyond
  EXPECT_NEAR(two.ranges[4], (0.14 + 0.16 + 0.18) / 3, 1e-12);
  EXPECT_NEAR(two.ranges[5], (0.14 + 0.16 + 0.18 + 0.16 + 0.12) / 5, 1e-12);
  EXPECT_NEAR(two.ranges[6], (0.16 + 0.18 + 0.16 + 0.12 + 0.10) / 5, 1e-12);
  // However wide the window, it never reaches across the saturated reading.
  EXPECT_EQ(smooth_ir_scan(hand_scan(), 100).ranges, smooth_ir_scan(hand_scan(), 3).ranges);
}

TEST(SmoothIrScan, TheWindowDoesNotCrossAJump) {
  RangeScan in = hand_scan();
  in.ranges[5] = 0.25;  // 9 cm beyond reading 4 and 6: another wall
  const RangeScan out = smooth_ir_scan(in, 1);
  EXPECT_EQ(out.ranges[4], 0.16);
  EXPECT_EQ(out.ranges[5], 0.25);
  EXPECT_EQ(out.ranges[6], 0.16);
}

TEST(SmoothIrScan, ZeroWindowKeepsTheScanAndNegativeThrows) {
  EXPECT_EQ(smooth_ir_scan(hand_scan(), 0).ranges, hand_scan().ranges);
  expect_error([] { smooth_ir_scan(hand_scan(), -1); }, {"half_window", "-1"});
  RangeScan bad = hand_scan();
  bad.angles.pop_back();
  expect_error([&] { smooth_ir_scan(bad, 1); }, {"7 angles", "8 ranges"});
}

/// Options for the reader without smoothing.
IrSensorOptions unsmoothed() {
  IrSensorOptions o;
  o.smoothing_half_window = 0;
  return o;
}

TEST(LoadIrScanCsv, ReadsDegreesAndCentimetresFromTheHeader) {
  TempDir dir;
  const std::string path = dir.write("scan.csv",
                                     "# a GP2D12 turn\n"
                                     "angle_deg,range_cm\n"
                                     "-180,20\n0,25\n45,40\n90, 5\n"
                                     "\n"
                                     "135,29.99999\n180,30\n225,inf\n270,12.5 # wall\n");
  const RangeScan s = load_ir_scan_csv(path, unsmoothed());
  ASSERT_EQ(s.ranges.size(), 8u);
  EXPECT_EQ(s.max_range, 0.30);
  EXPECT_DOUBLE_EQ(s.angles[0], -std::numbers::pi);
  EXPECT_DOUBLE_EQ(s.angles[2], std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(s.angles[7], 1.5 * std::numbers::pi);
  EXPECT_DOUBLE_EQ(s.ranges[0], 0.20);
  EXPECT_DOUBLE_EQ(s.ranges[1], 0.25);
  EXPECT_EQ(s.ranges[2], 0.30);         // beyond the truncation: saturated
  EXPECT_EQ(s.ranges[3], 0.09);         // nearer than the calibration: min range
  EXPECT_EQ(s.ranges[4], 0.30 - 1e-6);  // just below max stays a return
  EXPECT_EQ(s.ranges[5], 0.30);         // at max: saturated
  EXPECT_EQ(s.ranges[6], 0.30);         // inf: no wall
  EXPECT_DOUBLE_EQ(s.ranges[7], 0.125);
}

TEST(LoadIrScanCsv, RadiansAndMetresByDefaultAndSmoothed) {
  TempDir dir;
  std::string text = "# no header\n";
  const std::vector<double> ranges = {0.10, 0.12, 0.50, 0.14, 0.16, 0.18, 0.20, 0.22};
  for (int k = 0; k < 8; ++k) {
    text += std::to_string(-std::numbers::pi + k * std::numbers::pi / 4) + "," +
            std::to_string(ranges[k]) + "\n";
  }
  const std::string path = dir.write("scan.csv", text);
  const RangeScan raw = load_ir_scan_csv(path, unsmoothed());
  ASSERT_EQ(raw.ranges.size(), 8u);
  EXPECT_NEAR(raw.angles[1], -0.75 * std::numbers::pi, 1e-6);
  EXPECT_DOUBLE_EQ(raw.ranges[1], 0.12);
  EXPECT_EQ(raw.ranges[2], 0.30);
  IrSensorOptions o;
  o.smoothing_half_window = 1;
  const RangeScan smoothed = load_ir_scan_csv(path, o);
  EXPECT_EQ(smoothed.ranges, smooth_ir_scan(raw, 1).ranges);
  EXPECT_NEAR(smoothed.ranges[4], (0.14 + 0.16 + 0.18) / 3, 1e-12);
}

TEST(LoadIrScanCsv, ErrorsNameTheFileAndLine) {
  TempDir dir;
  const std::string eight = "0,0.1\n1,0.1\n2,0.1\n3,0.1\n4,0.1\n5,0.1\n6,0.1\n";
  const std::string nan_file = dir.write("nan.csv", "angle_rad,range_m\n0,0.1\n\n1,nan\n" + eight);
  expect_error([&] { load_ir_scan_csv(nan_file, unsmoothed()); }, {nan_file + ":4", "NaN"});
  const std::string negative = dir.write("neg.csv", eight + "# x\n7,-0.01\n");
  expect_error([&] { load_ir_scan_csv(negative, unsmoothed()); }, {negative + ":9", "negative"});
  const std::string word = dir.write("word.csv", eight + "7,abc\n");
  expect_error([&] { load_ir_scan_csv(word, unsmoothed()); }, {word + ":8", "abc"});
  const std::string three = dir.write("three.csv", eight + "7,0.1,2\n");
  expect_error([&] { load_ir_scan_csv(three, unsmoothed()); }, {three + ":8", "angle,range"});
  const std::string header = dir.write("header.csv", "# c\nangle_grad,range_cm\n" + eight);
  expect_error([&] { load_ir_scan_csv(header, unsmoothed()); }, {header + ":2", "angle_grad"});
  const std::string late = dir.write("late.csv", eight + "angle_deg,range_cm\n");
  expect_error([&] { load_ir_scan_csv(late, unsmoothed()); }, {late + ":8", "angle_deg"});
  const std::string few = dir.write("few.csv", eight);
  expect_error([&] { load_ir_scan_csv(few, unsmoothed()); }, {few, "7 readings"});
  const std::string missing = dir.file("missing.csv");
  expect_error([&] { load_ir_scan_csv(missing, unsmoothed()); }, {missing, "not found"});
  ResourceLimits limits;
  limits.max_beams = 5;
  const std::string many = dir.write("many.csv", eight + "7,0.1\n");
  expect_error([&] { load_ir_scan_csv(many, unsmoothed(), limits); }, {many + ":6", "--max-beams"});
}

TEST(ValidateIrSensorOptions, NamesTheField) {
  EXPECT_NO_THROW(validate(IrSensorOptions{}));
  IrSensorOptions o;
  o.readings = 7;
  expect_error([&] { validate(o); }, {"readings", "7"});
  o.readings = 100'001;
  expect_error([&] { validate(o); }, {"readings"});
  o = {};
  o.min_range_m = 0.0;
  expect_error([&] { validate(o); }, {"min_range_m"});
  o.min_range_m = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { validate(o); }, {"min_range_m"});
  o = {};
  o.max_range_m = 0.09;
  expect_error([&] { validate(o); }, {"max_range_m"});
  o.max_range_m = std::numeric_limits<double>::infinity();
  expect_error([&] { validate(o); }, {"max_range_m"});
  o = {};
  o.smoothing_half_window = -1;
  expect_error([&] { validate(o); }, {"smoothing_half_window"});
  o.smoothing_half_window = 180;  // of 360 readings
  expect_error([&] { validate(o); }, {"smoothing_half_window", "180"});
  o.smoothing_half_window = 179;
  EXPECT_NO_THROW(validate(o));
}

}  // namespace
}  // namespace gridloc
