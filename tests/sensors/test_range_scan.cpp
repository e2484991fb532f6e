// Tests of sensors/src/range_scan.cpp: the laser/IR scan model, its validation and CSV input,
// rigid scan points and their rasterization against a brute-force reference (fixed seeds),
// the canvas's sorted collect (sparse and dense paths), and localization of the shared
// peer-comparison scans (skipped when ../shared is absent).
#include "gridloc/sensors/range_scan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/map_io.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::random_scan;
using test::uniform_int;
using test::uniform_real;

constexpr double kRes = 0.1;

double sum_of(const SparseLocalGrid& g, bool positive) {
  double s = 0.0;
  for (float v : g.value) s += (v > 0.0f) == positive ? v : 0.0f;
  return s;
}

TEST(RangeScan, OneBeamHasAnEndCellAndMinusOneBeforeIt) {
  for (double angle : {0.0, 0.4, 1.9, -2.7}) {
    const RangeScan scan{{angle}, {3.0}, 8.0};
    for (ScanModel model : {ScanModel::Rays, ScanModel::Samples}) {
      const SparseLocalGrid f =
          rasterize_scan(scan, 0.25, kRes, Eigen::Vector2d::Zero(), {model, 4});
      EXPECT_NEAR(sum_of(f, false), -1.0, 1e-5) << angle;  // the free part shares -1
    }
    const SparseLocalGrid g = rasterize_scan(scan, 0.25, kRes);  // hits: the end cell only
    EXPECT_EQ(g.size(), 1u) << angle;
    EXPECT_DOUBLE_EQ(sum_of(g, true), 1.0) << angle;
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
  const SparseLocalGrid g =
      rasterize_scan(scan, 0.0, kRes, Eigen::Vector2d::Zero(), {ScanModel::Rays});
  EXPECT_DOUBLE_EQ(sum_of(g, true), 1.0);  // only the second beam hits
  EXPECT_GE(g.extent(), 79);               // the first beam's free cells reach 8 m
  // Samples: the last of 4 lies at 7/8 of the range.
  const SparseLocalGrid s =
      rasterize_scan(scan, 0.0, kRes, Eigen::Vector2d::Zero(), {ScanModel::Samples, 4});
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

TEST(RangeScanErrors, NonFiniteOrFarCentre) {
  const RangeScan scan{{0.0, 1.0}, {8.0, 2.0}, 8.0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& centre : {Eigen::Vector2d(nan, 0.0), Eigen::Vector2d(0.0, -inf)}) {
    for (ScanModel model : {ScanModel::Rays, ScanModel::Samples, ScanModel::Hits}) {
      test::expect_error(
          [&] {
            (void)rasterize_scan(scan, 0.0, kRes, centre, {model, 4});
          },
          {"local grid centre", "finite"});
    }
    test::expect_error(
        [&] {
          (void)rasterize_points(scan_points(scan, {ScanModel::Hits, 1}), 0.0, kRes, centre);
        },
        {"local grid centre", "finite"});
  }
  // Finite but far: the canvas's cell indices would overflow.
  test::expect_error(
      [&] {
        (void)rasterize_scan(scan, 0.0, kRes, {1e300, 0.0});
      },
      {"canvas", "46339"});
  test::expect_error([&] { (void)rasterize_scan(scan, 0.0, 1e-5); }, {"canvas", "46339"});
  // A centre within the robot's cell still rasterizes.
  EXPECT_GT(rasterize_scan(scan, 0.0, kRes, {0.04, -0.03}).size(), 0u);
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
/// search from the bench case README's start poses.
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

// --- Rigid scan points (ScanModel::Samples and Hits) and their rasterization ---------------

/// The brute-force rasterization of rigid points: each point's cell by point_cell; a cell
/// holding a beam end is exactly +1, any other the float sum of its free samples' weights in
/// point order; zero cells dropped; sorted by (dy, dx).
SparseLocalGrid rasterize_points_reference(const ScanPoints& p, double theta, double resolution,
                                           const Eigen::Vector2d& centre) {
  const double inv = 1.0 / resolution;
  const double cx = centre.x() * inv, cy = centre.y() * inv;
  const double c = std::cos(theta), s = std::sin(theta);
  std::set<std::pair<int, int>> hits;        // (dy, dx)
  std::map<std::pair<int, int>, float> sum;  // (dy, dx) -> free weights
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Eigen::Vector2i cell = point_cell(p, k, c, s, inv, cx, cy);
    const std::pair<int, int> key{cell.y(), cell.x()};
    if (k < p.hit_count) {
      hits.insert(key);
    } else {
      sum[key] += p.weight[k];  // value-initialized to 0.0f, then added in point order
    }
  }
  std::map<std::pair<int, int>, float> cells = sum;
  for (const auto& key : hits) cells[key] = 1.0f;
  SparseLocalGrid g;
  g.resolution = resolution;
  g.theta = theta;
  for (const auto& [key, v] : cells) {
    if (v == 0.0f) continue;
    g.dx.push_back(key.second);
    g.dy.push_back(key.first);
    g.value.push_back(v);
  }
  return g;
}

/// Exact equality of two local grids, cell by cell.
void expect_same_grid(const SparseLocalGrid& a, const SparseLocalGrid& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.dx.size(), a.size()) << what;
  ASSERT_EQ(a.dy.size(), a.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.dx[k], b.dx[k]) << what << " cell " << k;
    ASSERT_EQ(a.dy[k], b.dy[k]) << what << " cell " << k;
    ASSERT_EQ(a.value[k], b.value[k]) << what << " cell " << k;
  }
}

/// Cells strictly increasing in (dy, dx): sorted, no cell twice.
void expect_sorted_unique(const SparseLocalGrid& g, const std::string& what) {
  ASSERT_EQ(g.dx.size(), g.size()) << what;
  ASSERT_EQ(g.dy.size(), g.size()) << what;
  for (std::size_t k = 1; k < g.size(); ++k) {
    ASSERT_LT(std::pair(g.dy[k - 1], g.dx[k - 1]), std::pair(g.dy[k], g.dx[k]))
        << what << " cell " << k;
  }
  for (float v : g.value) ASSERT_NE(v, 0.0f) << what;
}

TEST(RangeScanPoints, HoldBeamEndsThenEqualFreeSamples) {
  const RangeScan scan{{0.0, 1.0, 2.0, -1.5}, {2.0, 8.0, 0.5, 9.5}, 8.0};
  const ScanPoints p = scan_points(scan, {ScanModel::Samples, 3});
  ASSERT_EQ(p.hit_count, 2u);  // beams 0 and 2 return
  ASSERT_EQ(p.size(), 2u + 4u * 3u);
  ASSERT_EQ(p.x.size(), p.size());
  ASSERT_EQ(p.y.size(), p.size());
  ASSERT_EQ(p.norm.size(), p.size());
  EXPECT_EQ(p.weight[0], 1.0f);
  EXPECT_EQ(p.weight[1], 1.0f);
  EXPECT_NEAR(p.x[0], 2.0, 1e-12);
  EXPECT_NEAR(p.y[1], 0.5 * std::sin(2.0), 1e-12);
  for (std::size_t k = p.hit_count; k < p.size(); ++k) EXPECT_EQ(p.weight[k], -1.0f / 3.0f) << k;
  EXPECT_DOUBLE_EQ(p.max_norm, 8.0 * 5.0 / 6.0);  // a no-return beam's last sample, at 5/6
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_NEAR(std::hypot(p.x[k], p.y[k]), p.norm[k], 1e-12) << k;
    EXPECT_LE(p.norm[k], p.max_norm) << k;
  }
  const ScanPoints h = scan_points(scan, {ScanModel::Hits, 0});  // free_samples unused
  EXPECT_EQ(h.hit_count, 2u);
  EXPECT_EQ(h.size(), 2u);
  EXPECT_DOUBLE_EQ(h.max_norm, 2.0);
}

TEST(RangeScanPoints, RaysHaveNoPointsAndFreeSamplesAreChecked) {
  const RangeScan scan{{0.0, 1.0}, {2.0, 3.0}, 8.0};
  test::expect_error([&] { (void)scan_points(scan, {ScanModel::Rays, 4}); }, {"ray"});
  EXPECT_THROW((void)scan_points(scan, {ScanModel::Rays, 4}), Error);
  for (int bad : {0, -1, 1001}) {
    test::expect_error(
        [&] {
          validate(ScanModelOptions{ScanModel::Samples, bad});
        },
        {"free_samples", std::to_string(bad)});
    test::expect_error(
        [&] {
          (void)scan_points(scan, {ScanModel::Samples, bad});
        },
        {"free_samples"});
    test::expect_error(
        [&] {
          (void)rasterize_scan(scan, 0.0, kRes, Eigen::Vector2d::Zero(), {ScanModel::Samples, bad});
        },
        {"free_samples"});
  }
  EXPECT_NO_THROW(validate(ScanModelOptions{ScanModel::Samples, 1}));
  EXPECT_NO_THROW(validate(ScanModelOptions{ScanModel::Samples, 1000}));
  EXPECT_NO_THROW(validate(ScanModelOptions{ScanModel::Hits, 0}));
}

TEST(RangeScanRasterizePoints, EqualsBruteForceReferenceOnRandomScans) {
  std::mt19937 rng(4242);
  long long cells = 0;
  for (int c = 0; c < 400; ++c) {
    const double res = c % 2 == 0 ? 0.05 : 0.1;
    const int beams = uniform_int(rng, 1, c % 10 == 0 ? 360 : 60);
    const RangeScan scan = random_scan(rng, beams, uniform_real(rng, 0.2, 8.0));
    const ScanModelOptions model =
        c % 4 == 3 ? ScanModelOptions{ScanModel::Hits, 4}
                   : ScanModelOptions{ScanModel::Samples, uniform_int(rng, 1, c % 8 == 0 ? 12 : 5)};
    const ScanPoints p = scan_points(scan, model);
    for (int t = 0; t < 3; ++t) {
      const double theta = uniform_real(rng, -7.0, 7.0);
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      if (t > 0) {  // within the robot's cell, or anywhere within a metre
        const double r = t == 1 ? 0.5 * res : 1.0;
        centre = {uniform_real(rng, -r, r), uniform_real(rng, -r, r)};
      }
      const std::string what = "case " + std::to_string(c) + " t " + std::to_string(t);
      const SparseLocalGrid g = rasterize_points(p, theta, res, centre);
      EXPECT_EQ(g.resolution, res) << what;
      EXPECT_EQ(g.theta, theta) << what;
      expect_same_grid(g, rasterize_points_reference(p, theta, res, centre), what);
      expect_sorted_unique(g, what);
      // rasterize_scan under the same model is rasterize_points of the scan's points.
      expect_same_grid(rasterize_scan(scan, theta, res, centre, model), g, what + " scan");
      cells += static_cast<long long>(g.size());
    }
  }
  EXPECT_GT(cells, 20000);
}

TEST(RangeScanRasterizePoints, DefaultModelIsHits) {
  std::mt19937 rng(8);
  const RangeScan scan = random_scan(rng, 50, 5.0);
  expect_same_grid(rasterize_scan(scan, 0.7, 0.05),
                   rasterize_points(scan_points(scan, {ScanModel::Hits, 4}), 0.7, 0.05), "default");
}

/// Sparse canvases collect by radix-sorting the written cells, dense ones by walking their
/// bounding box; both must give cells sorted by (dy, dx), each once.
TEST(RangeScanCanvasCollect, SparseAndDenseScansAreSortedWithoutDuplicates) {
  std::mt19937 rng(360);
  for (int c = 0; c < 6; ++c) {
    RangeScan scan;
    scan.max_range = 8.0;
    for (int k = 0; k < 360; ++k) {
      scan.angles.push_back(k * std::numbers::pi / 180.0);
      // Long beams (some without return): few cells per canvas area, the radix-sort path.
      scan.ranges.push_back(k % 17 == 0 ? 8.0 : uniform_real(rng, 5.0, 7.9));
    }
    const double theta = uniform_real(rng, -3.0, 3.0);
    const Eigen::Vector2d centre{uniform_real(rng, -0.02, 0.02), uniform_real(rng, -0.02, 0.02)};
    for (const ScanModelOptions model :
         {ScanModelOptions{ScanModel::Hits, 1}, ScanModelOptions{ScanModel::Samples, 1},
          ScanModelOptions{ScanModel::Samples, 3}}) {
      const std::string what =
          "case " + std::to_string(c) + " samples " + std::to_string(model.free_samples);
      const ScanPoints p = scan_points(scan, model);
      const SparseLocalGrid g = rasterize_points(p, theta, 0.05, centre);
      // Every written cell is non-zero, so g.size() cells were written on a canvas (in a
      // fresh process) `side` cells wide: few enough for the sparse (radix-sort) path.
      const auto side = static_cast<std::size_t>(
          2 * (static_cast<int>(std::ceil(p.max_norm / 0.05 + centre.norm() / 0.05)) + 2) + 1);
      EXPECT_LT(g.size() * 64, side * side) << what;
      EXPECT_GT(g.size(), 300u) << what;
      expect_sorted_unique(g, what);
      expect_same_grid(g, rasterize_points_reference(p, theta, 0.05, centre), what);
    }
    // The ray model marks every crossed cell: the dense path.
    const SparseLocalGrid rays = rasterize_scan(scan, theta, 0.05, centre, {ScanModel::Rays, 4});
    EXPECT_GT(rays.size() * 64, 327u * 327u) << c;  // the ray canvas is 327 cells wide
    expect_sorted_unique(rays, "rays case " + std::to_string(c));
    double positive = 0.0, negative = 0.0;
    for (float v : rays.value) (v > 0.0f ? positive : negative) += v;
    EXPECT_LE(positive, 360.0 - 22.0) << c;  // 22 beams have no return; ends may merge
    EXPECT_GT(positive, 100.0) << c;
    EXPECT_GE(negative, -360.0 - 1e-3) << c;  // -1 per beam, less where end cells beat it
    EXPECT_LE(negative, -0.95 * 360.0) << c;
  }
}

/// A canvas more than 2048 cells wide: three radix passes of 11 bits.
TEST(RangeScanCanvasCollect, WideCanvasNeedsThreeRadixPasses) {
  std::mt19937 rng(2049);
  RangeScan scan;
  scan.max_range = 12.0;
  for (int k = 0; k < 360; ++k) {
    scan.angles.push_back(uniform_real(rng, -std::numbers::pi, std::numbers::pi));
    scan.ranges.push_back(uniform_real(rng, 0.5, 11.9));
  }
  for (const ScanModelOptions model :
       {ScanModelOptions{ScanModel::Hits, 1}, ScanModelOptions{ScanModel::Samples, 2}}) {
    const ScanPoints p = scan_points(scan, model);
    for (double theta : {0.0, 1.1, -2.5}) {
      const Eigen::Vector2d centre{0.003, -0.004};
      const SparseLocalGrid g = rasterize_points(p, theta, 0.01, centre);  // > 2400 cells wide
      const std::string what =
          "samples " + std::to_string(model.free_samples) + " theta " + std::to_string(theta);
      expect_sorted_unique(g, what);
      expect_same_grid(g, rasterize_points_reference(p, theta, 0.01, centre), what);
    }
  }
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14: a directory is not an empty scan, and the beams are counted while reading.
TEST(RangeScanErrors, CsvLimits) {
  test::TempDir dir;
  test::expect_error([&] { load_scan_csv(dir.path().string(), 8.0); },
                     {dir.path().string(), "is a directory", "scan file"});
  const std::string p = dir.write("s.csv", "0,1\n0.1,1\n0.2,1\n");
  ResourceLimits two;
  two.max_beams = 2;
  test::expect_error([&] { load_scan_csv(p, 8.0, two); },
                     {"s.csv:3", "3 beams", "limit of 2 beams", "--max-beams"});
  two.max_beams = 3;
  EXPECT_EQ(load_scan_csv(p, 8.0, two).ranges.size(), 3u);
  ResourceLimits tiny_file;
  tiny_file.max_file_mb = 1e-6;
  test::expect_error([&] { load_scan_csv(p, 8.0, tiny_file); }, {p, "--max-file-mb"});
  const std::string long_line = dir.write("long.csv", "0," + std::string(100000, '1') + "\n");
  test::expect_error([&] { load_scan_csv(long_line, 8.0); }, {"long.csv:1", "longer than"});
}

}  // namespace
}  // namespace gridloc
