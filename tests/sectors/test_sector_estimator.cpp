// Tests of engine/src/sectors/estimator.cpp: the sector fix as an Estimate (verdicts,
// look-alikes, covariance) and its refinement by the correlation's local search.
#include "gridloc/engine/sectors/estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "test_support.hpp"

namespace gridloc {
namespace {

PolygonMap l_room() {
  return make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}}, {});
}

/// A window that covers the whole L (the sector estimator ignores it but for on_window_edge).
SearchWindow everywhere() {
  SearchWindow w;
  w.center = {3.5, 3.0, 0.0};
  w.half_xy = 4.0;
  w.half_theta = std::numbers::pi;
  return w;
}

Observation scan_at(const PolygonMap& m, const Pose2& pose) {
  return Observation{{}, polygon_scan(m, pose, 360, 20.0)};
}

/// A round room of radius 2 m: no corner, no label to match.
RangeScan round_room() {
  RangeScan round;
  round.max_range = 20.0;
  for (int k = 0; k < 360; ++k) {
    round.angles.push_back(deg2rad(k));
    round.ranges.push_back(2.0);
  }
  return round;
}

TEST(SectorEstimator, AFixIsLocalizedWithACovariance) {
  const PolygonMap m = l_room();
  const SectorEstimator sectors(m);
  const Pose2 truth{1.5, 1.5, 0.3};
  const SectorEstimate e = sectors.locate(scan_at(m, truth), everywhere());
  ASSERT_TRUE(e.fix.found);
  EXPECT_EQ(e.estimate.verdict, Verdict::Localized);
  EXPECT_LT(std::hypot(e.estimate.pose.x - truth.x, e.estimate.pose.y - truth.y), 0.02);
  EXPECT_GT(e.estimate.confidence, 0.8);  // a residual of millimetres
  EXPECT_EQ(e.estimate.alternatives.size(), 1u);
  EXPECT_TRUE(std::isnan(e.estimate.second_score));
  EXPECT_FALSE(e.estimate.on_window_edge);
  for (int k = 0; k < 3; ++k) EXPECT_GT(e.estimate.covariance(k, k), 0.0);
  EXPECT_EQ(e.fix.sector, sectors.sectors().sector_at({truth.x, truth.y}));
  // A window that does not hold the fix only says so.
  SearchWindow elsewhere = everywhere();
  elsewhere.center = {6.0, 1.5, 0.0};
  elsewhere.half_xy = 0.5;
  EXPECT_TRUE(sectors.estimate(scan_at(m, truth), elsewhere).on_window_edge);
}

TEST(SectorEstimator, LookAlikesAreAmbiguousWithTheirPoses) {
  // A plain rectangle: every pose has its twin turned by 180 deg about the centre.
  const PolygonMap m = make_polygon_map({{0, 0}, {6, 0}, {6, 4}, {0, 4}}, {});
  const SectorEstimator sectors(m);
  const Pose2 truth{1.5, 1.2, 0.4};
  const Estimate e = sectors.estimate(scan_at(m, truth), everywhere());
  EXPECT_EQ(e.verdict, Verdict::Ambiguous);
  EXPECT_TRUE(e.ambiguous);
  ASSERT_EQ(e.alternatives.size(), 2u);
  EXPECT_NEAR(e.second_score, e.alternatives[1].score, 1e-12);
  const Pose2 twin{6.0 - truth.x, 4.0 - truth.y, normalize_angle(truth.theta + std::numbers::pi)};
  int found = 0;
  for (const auto& a : e.alternatives) {
    for (const Pose2& p : {truth, twin}) {
      found += std::hypot(a.pose.x - p.x, a.pose.y - p.y) < 0.02 ? 1 : 0;
    }
  }
  EXPECT_EQ(found, 2);
}

TEST(SectorEstimator, NoMatchIsNotLocalizedAtTheWindowCentre) {
  const SectorEstimator sectors(l_room());
  const SearchWindow w = everywhere();
  const Estimate e = sectors.estimate(Observation{{}, round_room()}, w);
  EXPECT_EQ(e.verdict, Verdict::NotLocalized);
  EXPECT_EQ(e.confidence, 0.0);
  EXPECT_EQ(e.pose.x, w.center.x);
  EXPECT_EQ(e.pose.y, w.center.y);
}

TEST(SectorEstimator, ErrorsNameWhatIsWrong) {
  const SectorEstimator sectors(l_room());
  test::expect_error(
      [&] {
        sectors.estimate(Observation{{1.0, 2.0, 3.0}}, everywhere());
      },
      {"360 degree", "sonar"});
  SectorEstimatorOptions bad;
  bad.residual_scale_m = 0.0;
  test::expect_error([&] { SectorEstimator(l_room(), bad); }, {"residual_scale_m"});
  SearchWindow window = everywhere();
  window.half_xy = -1.0;
  test::expect_error(
      [&] {
        sectors.estimate(scan_at(l_room(), {1.5, 1.5, 0.3}), window);
      },
      {"half_xy"});
}

TEST(SectorCorrelationEstimator, RefinesTheFixAndKeepsItsVerdict) {
  const PolygonMap m = l_room();
  auto sectors = std::make_shared<const SectorEstimator>(m);
  CorrelationOptions fine;
  fine.resolution = 0.025;
  fine.reach_m = 20.0;
  auto local = std::make_shared<const CorrelationEstimator>(rasterize_polygon_map(m, 0.025), fine);
  const SectorCorrelationEstimator refined(sectors, local);
  EXPECT_EQ(refined.name(), "sectors+correlation");
  const Pose2 truth{4.5, 1.2, -0.8};
  const SectorEstimate r = refined.locate(scan_at(m, truth), everywhere());
  const SectorEstimate f = sectors->locate(scan_at(m, truth), everywhere());
  EXPECT_EQ(r.estimate.verdict, f.estimate.verdict);
  EXPECT_EQ(r.fix.sector, f.fix.sector);
  EXPECT_EQ(r.estimate.confidence, f.estimate.confidence);
  // The search's lattice pose, within a 2.5 cm cell and a heading step of the truth.
  EXPECT_LT(std::hypot(r.estimate.pose.x - truth.x, r.estimate.pose.y - truth.y), 0.03);
  EXPECT_LT(std::abs(normalize_angle(r.estimate.pose.theta - truth.theta)), deg2rad(0.5));
  EXPECT_GT(r.estimate.stats.cells_scored, 0);

  // Nothing matched: no search, the fix's "not localized".
  const SectorEstimate none = refined.locate(Observation{{}, round_room()}, everywhere());
  EXPECT_FALSE(none.fix.found);
  EXPECT_EQ(none.estimate.verdict, Verdict::NotLocalized);
  EXPECT_EQ(none.estimate.stats.cells_scored, 0);

  SectorCorrelationOptions bad;
  bad.half_xy = 0.0;
  test::expect_error([&] { SectorCorrelationEstimator(sectors, local, bad); }, {"half_xy"});
  test::expect_error([&] { SectorCorrelationEstimator(nullptr, local); }, {"needs a sector"});
}

}  // namespace
}  // namespace gridloc
