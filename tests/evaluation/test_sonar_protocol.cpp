// Tests of engine/src/evaluation/sonar_protocol.cpp: seed 001's evaluation protocol.
#include "gridloc/engine/evaluation/sonar_protocol.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>

#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

/// Floor on the success rate of oriented + thinned in the small run below (the full run of
/// 300 trials reaches 99-100 %; 20 per room leaves room for one or two unlucky draws).
constexpr double kOrientedThinnedFloor = 0.95;
/// The paper's ordering must show with a margin: oriented + thinned beats turned + raw by at
/// least this much (74 % vs 99 % in seed 001).
constexpr double kMinimumGain = 0.10;
constexpr int kTrialsPerMap = 20;

std::vector<EvalMap> bundled_rooms() {
  std::vector<EvalMap> maps;
  for (const char* name : {"room_rect", "room_l", "room_furnished"}) {
    maps.push_back({name, load_ros_map(test::map_path(name))});
  }
  return maps;
}

void print(const EvalReport& r) {
  std::printf("%-9s %-8s %9s %14s %16s %10s\n", "local", "global", "success", "mean pos err",
              "mean head err", "median");
  for (const auto& c : r.configurations) {
    std::printf("%-9s %-8s %8.1f%% %12.3f m %12.2f deg %7.2f ms\n",
                to_string(c.configuration.local).c_str(), to_string(c.configuration.global).c_str(),
                100.0 * c.success_rate, c.mean_position_error_m, c.mean_heading_error_deg,
                c.median_ms);
  }
  std::fflush(stdout);
}

const ConfigurationResult& find(const EvalReport& r, LocalModel l, GlobalModel g) {
  for (const auto& c : r.configurations) {
    if (c.configuration.local == l && c.configuration.global == g) return c;
  }
  throw std::runtime_error("configuration not in the report");
}

TEST(Evaluation, OrientedThinnedBeatsTurnedRaw) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EvalOptions o;
  o.trials = kTrialsPerMap;
  o.seed = 1;
  int calls = 0, last_done = 0;
  const EvalReport r = run_evaluation(bundled_rooms(), ring, o, [&](int done, int total) {
    ++calls;
    EXPECT_EQ(done, last_done + 1);
    EXPECT_EQ(total, 3 * kTrialsPerMap);
    last_done = done;
  });
  print(r);
  EXPECT_EQ(calls, 3 * kTrialsPerMap);
  EXPECT_EQ(r.trials, 3 * kTrialsPerMap);
  ASSERT_EQ(r.configurations.size(), 4u);
  for (const auto& c : r.configurations) {
    EXPECT_EQ(c.trials, 3 * kTrialsPerMap);
    EXPECT_EQ(c.success_rate, static_cast<double>(c.successes) / c.trials);
    EXPECT_GE(c.mean_position_error_m, 0.0);
    EXPECT_GE(c.mean_heading_error_deg, 0.0);
  }
  const auto& best = find(r, LocalModel::Oriented, GlobalModel::Thinned);
  const auto& baseline = find(r, LocalModel::Turned, GlobalModel::Raw);
  EXPECT_GE(best.success_rate, baseline.success_rate + kMinimumGain);
  EXPECT_GE(best.success_rate, kOrientedThinnedFloor);
}

TEST(Evaluation, DeterministicForASeed) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const std::vector<EvalMap> maps = {{"room_l", load_ros_map(test::map_path("room_l"))}};
  EvalOptions o;
  o.trials = 3;
  o.seed = 5;
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned}};
  const EvalReport a = run_evaluation(maps, ring, o);
  const EvalReport b = run_evaluation(maps, ring, o);
  ASSERT_EQ(a.configurations.size(), 1u);
  EXPECT_EQ(a.configurations[0].successes, b.configurations[0].successes);
  EXPECT_EQ(a.configurations[0].mean_position_error_m, b.configurations[0].mean_position_error_m);
  EXPECT_EQ(a.configurations[0].mean_heading_error_deg, b.configurations[0].mean_heading_error_deg);
}

TEST(Evaluation, BadOptions) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EvalOptions o;
  o.trials = 0;
  test::expect_error([&] { run_evaluation(bundled_rooms(), ring, o); }, {"trials"});
  o.trials = 1;
  test::expect_error([&] { run_evaluation({}, ring, o); }, {"no maps"});
}

TEST(Evaluation, LaserProtocolComparesTheEstimatorsOnTheSameTrials) {
  // Measured over 300 trials (engine/doc/correlation.md, "Comparing the estimators"):
  // correlation 100 %, icp 87 % (seed 001's +-0.8 m, +-45 deg priors are often beyond ICP's
  // reach), correlation + ICP 100 % with 1 mm mean error. 20 trials per room keep the
  // ordering with a margin.
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EvalOptions o;
  o.trials = kTrialsPerMap;
  o.laser.enabled = true;
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::Correlation},
                      {LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::Icp},
                      {LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::CorrelationIcp}};
  const EvalReport r = run_evaluation(bundled_rooms(), ring, o);
  ASSERT_EQ(r.configurations.size(), 3u);
  const auto& correlation = r.configurations[0];
  const auto& icp = r.configurations[1];
  const auto& both = r.configurations[2];
  EXPECT_GE(correlation.success_rate, 0.95);
  EXPECT_GE(both.success_rate, correlation.success_rate);
  EXPECT_GT(both.success_rate, icp.success_rate);  // the search brings ICP into its basin
  EXPECT_LT(both.mean_position_error_m, 0.5 * correlation.mean_position_error_m);
  // Every configuration saw the same truths: records come in trial order, one per config.
  for (std::size_t k = 0; k + 2 < r.records.size(); k += 3) {
    EXPECT_EQ(r.records[k].trial, r.records[k + 2].trial);
    EXPECT_EQ(r.records[k].map, r.records[k + 2].map);
  }
  // ICP's confidence is 0 when it did not converge or left the window: failures flagged.
  EXPECT_GT(icp.auroc, 0.9);
}

TEST(Evaluation, ASparseLaserFailsIcpWithoutEndingTheRun) {
  // 36 beams, 10 deg apart: ICP finds no segments; its trials fail (confidence 0) and the
  // correlation, alone or refined, carries on.
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EvalOptions o;
  o.trials = 3;
  o.laser.enabled = true;
  o.laser.beams = 36;
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::Icp},
                      {LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::CorrelationIcp}};
  const EvalReport r = run_evaluation(bundled_rooms(), ring, o);
  EXPECT_EQ(r.configurations[0].successes, 0);
  EXPECT_GE(r.configurations[1].success_rate, 0.75);
}

TEST(Evaluation, IcpNeedsTheLaserProtocol) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EvalOptions o;
  o.trials = 1;
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::Icp}};
  test::expect_error([&] { run_evaluation(bundled_rooms(), ring, o); }, {"icp", "--laser"});
  o.laser.enabled = true;
  o.echo_filter = EchoFilterOptions{};
  test::expect_error([&] { run_evaluation(bundled_rooms(), ring, o); }, {"echo filter", "laser"});
  EXPECT_EQ(parse_estimator_kind("correlation+icp"), EstimatorKind::CorrelationIcp);
  test::expect_error([] { parse_estimator_kind("pf"); },
                     {"correlation, icp, correlation+icp, sectors or sectors+correlation"});
  o.echo_filter.reset();
  o.configurations = {{LocalModel::Oriented, GlobalModel::Thinned, EstimatorKind::Sectors}};
  test::expect_error([&] { run_evaluation(bundled_rooms(), ring, o); },
                     {"sectors", "polygon maps", "run_sector_evaluation"});
}

TEST(Evaluation, ModelNames) {
  EXPECT_EQ(to_string(LocalModel::Oriented), "oriented");
  EXPECT_EQ(to_string(LocalModel::Turned), "turned");
  EXPECT_EQ(to_string(GlobalModel::Thinned), "thinned");
  EXPECT_EQ(to_string(GlobalModel::Raw), "raw");
}

}  // namespace
}  // namespace gridloc
