// Tests of sensors/src/echo_filter.cpp: the EERUF-like front-end that rejects echoes
// consecutive firings do not repeat, the rejection mask in the sonar local grid and in the
// estimator, the evaluation's --echo-filter protocol and its command-line flag.
#include "gridloc/sensors/echo_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_model.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#ifdef GRIDLOC_CLI_PATH
#include "cli_support.hpp"
#endif
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kNone = 6.0;  // the bundled ring's max range: no echo

class EchoFilter : public ::testing::Test {
 protected:
  SonarRing ring = load_sonar_ring(test::ring_path());

  /// A firing of the ring where every sonar reads `d`.
  std::vector<double> all(double d) const { return std::vector<double>(ring.sonars.size(), d); }
};

TEST_F(EchoFilter, AgreeingFiringsAreKeptAsTheirMedian) {
  std::vector<double> a = all(2.0), b = all(2.02), c = all(1.99);
  const FilteredReadings f = filter_echoes(ring, {a, b, c});
  ASSERT_EQ(f.ranges.size(), ring.sonars.size());
  ASSERT_EQ(f.rejected.size(), ring.sonars.size());
  EXPECT_EQ(f.rejected_count, 0);
  for (std::size_t i = 0; i < f.ranges.size(); ++i) {
    EXPECT_FALSE(f.rejected[i]) << i;
    EXPECT_DOUBLE_EQ(f.ranges[i], 2.0) << i;
  }
  // Two firings: the mean of the two.
  const FilteredReadings two = filter_echoes(ring, {a, b});
  EXPECT_EQ(two.rejected_count, 0);
  EXPECT_DOUBLE_EQ(two.ranges[0], 2.01);
}

TEST_F(EchoFilter, CrosstalkInOneFiringIsOutvotedOrRejected) {
  std::vector<double> a = all(2.5), b = all(2.51), c = all(2.49);
  b[3] = 0.6;  // another sonar's ping heard by sonar 3 in the second firing only
  // Three firings: the two that agree win, the short echo never reaches the reading.
  const FilteredReadings three = filter_echoes(ring, {a, b, c});
  EXPECT_EQ(three.rejected_count, 0);
  EXPECT_NEAR(three.ranges[3], 2.495, 1e-12);
  // Two firings: nothing to outvote it with, the sonar is rejected.
  const FilteredReadings two = filter_echoes(ring, {a, b});
  EXPECT_EQ(two.rejected_count, 1);
  EXPECT_TRUE(two.rejected[3]);
  for (std::size_t i = 0; i < two.rejected.size(); ++i) {
    EXPECT_EQ(two.rejected[i], i == 3) << i;
  }
  // Asking all three to agree rejects it too.
  EchoFilterOptions strict;
  strict.min_agreeing = 3;
  const FilteredReadings all_three = filter_echoes(ring, {a, b, c}, strict);
  EXPECT_EQ(all_three.rejected_count, 1);
  EXPECT_TRUE(all_three.rejected[3]);
}

TEST_F(EchoFilter, NoEchoTwiceIsNoEchoAndEchoVersusNoneDisagrees) {
  std::vector<double> a = all(1.5), b = all(1.5), c = all(1.5);
  a[0] = b[0] = kNone;
  c[0] = kNone + 0.5;  // beyond max range also means no echo
  a[1] = kNone;        // one dropout among three firings: the two echoes win
  b[2] = kNone;        // two firings, echo against no echo: rejected (below)
  const FilteredReadings three = filter_echoes(ring, {a, b, c});
  EXPECT_FALSE(three.rejected[0]);
  EXPECT_EQ(three.ranges[0], kNone);
  EXPECT_FALSE(three.rejected[1]);
  EXPECT_DOUBLE_EQ(three.ranges[1], 1.5);
  const FilteredReadings two = filter_echoes(ring, {a, b});
  EXPECT_FALSE(two.rejected[0]);
  EXPECT_EQ(two.ranges[0], kNone);
  EXPECT_TRUE(two.rejected[1]);
  EXPECT_TRUE(two.rejected[2]);
  EXPECT_EQ(two.rejected_count, 2);
  // A rejected sonar's range is still a valid reading (between the firings').
  EXPECT_GE(two.ranges[1], 1.5);
  EXPECT_LE(two.ranges[1], kNone);
  EXPECT_NO_THROW(validate_readings(ring, two.ranges, two.rejected));
}

TEST_F(EchoFilter, ToleranceGrowsWithRange) {
  // 5 cm + 3 % of the shorter range: 0.17 m at 4 m, 0.065 m at 0.5 m.
  std::vector<double> a = all(4.0), b = all(4.16);
  b[1] = 4.2;
  a[2] = 0.5;
  b[2] = 0.56;
  a[3] = 0.5;
  b[3] = 0.57;
  const FilteredReadings f = filter_echoes(ring, {a, b});
  EXPECT_FALSE(f.rejected[0]);
  EXPECT_TRUE(f.rejected[1]);
  EXPECT_FALSE(f.rejected[2]);
  EXPECT_TRUE(f.rejected[3]);
}

TEST_F(EchoFilter, BadInputNamesWhatIsWrong) {
  const std::vector<double> a = all(2.0);
  test::expect_error([&] { filter_echoes(ring, {a}); }, {"echo filter", "at least 2", "got 1"});
  test::expect_error([&] { filter_echoes(ring, {}); }, {"at least 2", "got 0"});
  std::vector<double> short_firing(13, 2.0);
  test::expect_error(
      [&] {
        filter_echoes(ring, {a, a, short_firing});
      },
      {"firing 2", "13 ranges", "expected 14"});
  std::vector<double> bad = a;
  bad[5] = std::nan("");
  test::expect_error([&] { filter_echoes(ring, {a, bad}); }, {"firing 1", "sonar 5", "NaN"});
  bad[5] = -0.3;
  test::expect_error([&] { filter_echoes(ring, {bad, a}); }, {"firing 0", "sonar 5", "negative"});
  EchoFilterOptions o;
  o.min_agreeing = 1;
  test::expect_error([&] { filter_echoes(ring, {a, a}, o); }, {"min_agreeing", "1", ">= 2"});
  o = {};
  o.tolerance_m = -0.01;
  test::expect_error([&] { filter_echoes(ring, {a, a}, o); }, {"tolerance_m"});
  o = {};
  o.tolerance_frac = std::nan("");
  test::expect_error([&] { filter_echoes(ring, {a, a}, o); }, {"tolerance_frac"});
}

TEST_F(EchoFilter, ValidateReadingsChecksTheMask) {
  const std::vector<double> r = all(2.0);
  EXPECT_NO_THROW(validate_readings(ring, r, {}));
  std::vector<bool> mask(ring.sonars.size(), false);
  mask[4] = true;
  EXPECT_NO_THROW(validate_readings(ring, r, mask));
  test::expect_error([&] { validate_readings(ring, r, std::vector<bool>(3, false)); },
                     {"rejection mask", "3 flags", "expected 14"});
  test::expect_error(
      [&] { validate_readings(ring, r, std::vector<bool>(ring.sonars.size(), true)); },
      {"every reading was rejected"});
}

using CellMap = std::map<std::pair<int, int>, float>;
CellMap cells_of(const SparseLocalGrid& g) {
  CellMap m;
  for (std::size_t k = 0; k < g.size(); ++k) m[{g.dx[k], g.dy[k]}] = g.value[k];
  return m;
}

TEST_F(EchoFilter, RejectedSonarLeavesNoCellsInTheLocalGrid) {
  std::vector<double> ranges = all(2.0);
  ranges[5] = 1.2;
  ranges[9] = kNone;  // no echo: a free cone, unlike a rejected sonar
  for (int rejected : {5, 9}) {
    std::vector<bool> mask(ring.sonars.size(), false);
    mask[static_cast<std::size_t>(rejected)] = true;
    SonarRing without = ring;
    without.sonars.erase(without.sonars.begin() + rejected);
    std::vector<double> fewer = ranges;
    fewer.erase(fewer.begin() + rejected);
    for (LocalModel model : {LocalModel::Oriented, LocalModel::Turned}) {
      for (double theta : {0.0, 0.7, -2.1}) {
        const CellMap masked =
            cells_of(rasterize(ring, ranges, theta, 0.1, model, Eigen::Vector2d::Zero(), {}, mask));
        const CellMap absent = cells_of(rasterize(without, fewer, theta, 0.1, model));
        EXPECT_EQ(masked, absent) << "sonar " << rejected << ", theta " << theta;
        const CellMap full = cells_of(rasterize(ring, ranges, theta, 0.1, model));
        EXPECT_NE(masked, full) << "sonar " << rejected << ", theta " << theta;
      }
    }
  }
  // An all-false mask changes nothing.
  const std::vector<bool> none(ring.sonars.size(), false);
  EXPECT_EQ(cells_of(rasterize_oriented(ring, ranges, 0.3, 0.1, Eigen::Vector2d::Zero(), {}, none)),
            cells_of(rasterize_oriented(ring, ranges, 0.3, 0.1)));
}

class EchoFilterLocalization : public EchoFilter {
 protected:
  OccupancyMap map = load_ros_map(test::map_path("room_rect"));
};

TEST_F(EchoFilterLocalization, FilterRejectsCrosstalkAndTheEstimateIsCorrect) {
  const Pose2 truth{2.0, 1.5, 0.5};
  SonarSimOptions noise;
  noise.range_sigma_m = 0.01;
  noise.seed = 11;
  std::vector<double> first = simulate_sonar(map, ring, truth, noise);
  noise.seed = 12;
  std::vector<double> second = simulate_sonar(map, ring, truth, noise);
  // Crosstalk in the second firing: five sonars hear short echoes of their neighbours.
  const std::vector<int> corrupted = {0, 1, 4, 5, 12};
  for (int i : corrupted) second[static_cast<std::size_t>(i)] = 0.35 + 0.05 * i;
  const FilteredReadings f = filter_echoes(ring, {first, second});
  EXPECT_EQ(f.rejected_count, static_cast<int>(corrupted.size()));
  for (int i : corrupted) EXPECT_TRUE(f.rejected[static_cast<std::size_t>(i)]) << i;

  const CorrelationEstimator estimator(map, ring);
  SearchWindow window;
  window.center = {2.4, 1.2, 0.1};
  const Observation filtered{f.ranges, std::nullopt, f.rejected};
  const Estimate e = estimator.estimate(filtered, window);
  EXPECT_LE(std::hypot(e.pose.x - truth.x, e.pose.y - truth.y), 0.10);
  EXPECT_LE(rad2deg(std::abs(normalize_angle(e.pose.theta - truth.theta))), 7.0);
  // Every reading that reached the grid is explained by the map at the estimate.
  EXPECT_GT(e.agreement, 0.85);
  // The corrupted firing alone: its crosstalk echoes are not explained by the map.
  const Estimate raw = estimator.estimate(Observation{second}, window);
  EXPECT_LT(raw.agreement, e.agreement);
}

TEST_F(EchoFilterLocalization, EstimatorChecksTheMask) {
  const CorrelationEstimator estimator(map, ring);
  SearchWindow window;
  window.center = {2.0, 1.5, 0.5};
  const std::vector<double> r = simulate_sonar(map, ring, window.center);
  test::expect_error(
      [&] {
        estimator.estimate(
            Observation{r, std::nullopt, std::vector<bool>(ring.sonars.size(), true)}, window);
      },
      {"every reading was rejected"});
  test::expect_error(
      [&] {
        estimator.estimate(Observation{r, std::nullopt, std::vector<bool>(2, false)}, window);
      },
      {"rejection mask", "2 flags"});
}

TEST_F(EchoFilterLocalization, EvaluationWithTheFilterKeepsPosesAndPriors) {
  EvalOptions o;
  o.trials = 6;
  o.noisy.enabled = true;
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned}};
  const EvalReport plain = run_evaluation({{"room_rect", map}}, ring, o);
  o.echo_filter = EchoFilterOptions{};
  const EvalReport filtered = run_evaluation({{"room_rect", map}}, ring, o);
  ASSERT_EQ(plain.records.size(), filtered.records.size());
  int rejected = 0;
  for (std::size_t k = 0; k < plain.records.size(); ++k) {
    // Same truth and prior draws: the furniture and wrong-prior flags match trial by trial.
    EXPECT_EQ(plain.records[k].wrong_prior, filtered.records[k].wrong_prior) << k;
    EXPECT_EQ(plain.records[k].furniture, filtered.records[k].furniture) << k;
    EXPECT_EQ(plain.records[k].rejected_sonars, 0);
    rejected += filtered.records[k].rejected_sonars;
  }
  EXPECT_GT(rejected, 0) << "harsh noise over 3 firings should make some sonar disagree";
  o.echo_firings = 1;
  test::expect_error([&] { run_evaluation({{"room_rect", map}}, ring, o); }, {"echo_firings"});
}

#ifdef GRIDLOC_CLI_PATH
TEST(EchoFilterCli, EvalEchoFilterFlagRunsAndSaysSo) {
  const test::TempDir dir;
  const test::CliRun on =
      test::run_cli(dir, "eval --echo-filter --noisy --trials 3 --maps room_rect --json --quiet");
  ASSERT_EQ(on.status, 0) << on.err;
  EXPECT_NE(on.out.find("\"echo_filter\": true"), std::string::npos) << on.out;
  EXPECT_NE(on.out.find("\"configurations\""), std::string::npos) << on.out;
  // Without the flag the JSON says false.
  const test::CliRun off = test::run_cli(dir, "eval --trials 1 --maps room_rect --json --quiet");
  ASSERT_EQ(off.status, 0) << off.err;
  EXPECT_NE(off.out.find("\"echo_filter\": false"), std::string::npos) << off.out;
}
#endif

}  // namespace
}  // namespace gridloc
