// The correlation search on a likelihood-field global grid (GlobalModel::LikelihoodField):
// its int8 copies hold the field's 127 levels exactly, branch and bound equals the exhaustive
// search bit for bit on random maps and scans and on the sonar ring, and the estimate's
// normalized score and confidence stay in [0, 1].
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "correlation/scan_cases.hpp"
#include "correlation/search_cases.hpp"
#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/evidence.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "random_cases.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using namespace test;

/// A random map of walls (straight runs of occupied cells), free space and unknown patches.
OccupancyMap random_map(std::mt19937& rng, int w, int h, double res) {
  GridGeometry g;
  g.resolution = res;
  g.width = w;
  g.height = h;
  OccupancyMap m(g, CellState::Free);
  for (int k = uniform_int(rng, 0, 6); k > 0; --k) {
    const int x = uniform_int(rng, 0, w - 1), y = uniform_int(rng, 0, h - 1);
    const int len = uniform_int(rng, 1, 15);
    const bool across = uniform_int(rng, 0, 1) == 0;
    for (int i = 0; i < len; ++i) {
      const int cx = across ? x + i : x, cy = across ? y : y + i;
      if (g.contains(cx, cy)) m.at(cx, cy) = CellState::Occupied;
    }
  }
  for (auto& c : m.cells) {
    if (c == CellState::Free && uniform_int(rng, 0, 9) == 0) c = CellState::Unknown;
  }
  return m;
}

LikelihoodFieldOptions random_field(std::mt19937& rng) {
  LikelihoodFieldOptions o;
  o.sigma_m = uniform_real(rng, 0.03, 0.4);
  o.cutoff_m = uniform_real(rng, 0.0, 0.6);
  o.free_value = uniform_int(rng, 0, 2) == 0 ? 0.0 : -uniform_real(rng, 0.0, 1.0);
  return o;
}

SearchLevel level_of(const PaddedGrid& padded, const std::vector<SparseLocalGrid>& locals) {
  return {&padded, [&locals](double theta, const auto&...) {
            return locals[static_cast<std::size_t>(std::lround(theta))];
          }};
}

TEST(LikelihoodFieldSearch, PaddedFieldKeepsItsLevelsInInt8) {
  std::mt19937 rng(3);
  const OccupancyMap m = random_map(rng, 30, 20, 0.1);
  const EvidenceGrid field = make_likelihood_field(m, {});
  const PaddedGrid p = pad_grid(field, 4);
  ASSERT_TRUE(p.has_int8());
  EXPECT_FALSE(p.ternary());
  EXPECT_TRUE(p.grid.cells.empty());  // the int8 cells stand for the floats
  EXPECT_EQ(p.int8_scale, static_cast<float>(kFieldLevels));
  for (int iy = 0; iy < field.height(); ++iy) {
    for (int ix = 0; ix < field.width(); ++ix) {
      const std::size_t i = p.grid.geometry.index(ix + 4, iy + 4);
      EXPECT_EQ(static_cast<float>(p.grid8[i]) / kFieldLevels, field.at(ix, iy));
      EXPECT_EQ(static_cast<float>(p.arc_view8()[i]) / kFieldLevels,
                std::max(field.at(ix, iy), 0.0f));
    }
  }
  // Thinned grids keep their -1/0/1 copies.
  const PaddedGrid t = pad_grid(make_thinned_evidence(m), 4);
  EXPECT_TRUE(t.ternary());
  EXPECT_EQ(t.int8_scale, 1.0f);
}

TEST(LikelihoodFieldSearch, FixedPointScoreIsTheFieldsSum) {
  // Unit local values on the field: the score is the sum of the levels read, over 127.
  std::mt19937 rng(11);
  const OccupancyMap m = random_map(rng, 25, 25, 0.1);
  const EvidenceGrid field = make_likelihood_field(m, {});
  const PaddedGrid p = pad_grid(field, 6, ArcRule::Signed);
  for (int c = 0; c < 50; ++c) {
    SparseLocalGrid local = make_local(rng, uniform_int(rng, 1, 30), 5, 0);
    PlacedLocalGrid placed = place(local, p);
    ASSERT_GE(placed.fixed_shift, 0);
    const int cx = uniform_int(rng, 0, 24), cy = uniform_int(rng, 0, 24);
    long long levels = 0;
    for (std::size_t k = 0; k < local.size(); ++k) {
      const int x = cx + local.dx[k], y = cy + local.dy[k];
      if (!field.geometry.contains(x, y)) continue;
      levels += std::lround(local.value[k] * field.at(x, y) * kFieldLevels);
    }
    EXPECT_EQ(score(p, placed, cx, cy), static_cast<double>(levels) / kFieldLevels) << c;
    EXPECT_NEAR(score(p, placed, cx, cy), score_reference(field, local, cx, cy, ArcRule::Signed),
                1e-5);
  }
}

TEST(LikelihoodFieldSearch, BranchAndBoundEqualsExhaustiveOnRandomMaps) {
  std::mt19937 rng(2026);
  for (int c = 0; c < 200; ++c) {
    const int w = uniform_int(rng, 1, 30), h = uniform_int(rng, 1, 30);
    const EvidenceGrid field = make_likelihood_field(random_map(rng, w, h, 0.1), random_field(rng));
    const int headings = uniform_int(rng, 1, 4);
    const int value_kind = uniform_int(rng, 0, 2);  // fixed point, sonar-like, floats
    std::vector<SparseLocalGrid> locals;
    int extent = 0;
    for (int it = 0; it < headings; ++it) {
      locals.push_back(
          make_local(rng, uniform_int(rng, 0, 40), uniform_int(rng, 0, 8), value_kind));
      extent = std::max(extent, locals.back().extent());
    }
    const Lattice lat = make_lattice(rng, w, h, headings);
    for (ArcRule rule : kRules) {
      const PaddedGrid padded = pad_grid(field, extent + 1, rule);
      const BoundPyramid pyramid = make_bound_pyramid(padded, bound_depth_for(lat));
      ASSERT_TRUE(pyramid.has_int8());
      const SearchLevel level = level_of(padded, locals);
      const SearchResult e = search_exhaustive(lat, level);
      const SearchResult b = search_branch_and_bound(lat, level, pyramid);
      const std::string what = "case " + std::to_string(c) + " kind " + std::to_string(value_kind);
      expect_pose(b.best, e.best, what);
      expect_leaves_exact(b, e, lat, what);
    }
  }
}

TEST(LikelihoodFieldSearch, BranchAndBoundEqualsExhaustiveOnScans) {
  std::mt19937 rng(77);
  for (int c = 0; c < 120; ++c) {
    ScanCase s = make_scan_case(rng, c);
    const double res = s.grid.geometry.resolution;
    // The case's grid read as a map: > 0 occupied, < 0 free, 0 unknown; then its field.
    OccupancyMap m(s.grid.geometry, CellState::Unknown);
    for (std::size_t i = 0; i < m.cells.size(); ++i) {
      const float v = s.grid.cells[i];
      m.cells[i] = v > 0.0f ? CellState::Occupied : v < 0.0f ? CellState::Free : CellState::Unknown;
    }
    LikelihoodFieldOptions o = random_field(rng);
    o.sigma_m = std::max(o.sigma_m, res / 2);
    const PaddedGrid padded = pad_grid(make_likelihood_field(m, o), s.pad, s.rule);
    const BoundPyramid pyramid = make_bound_pyramid(padded, s.depth);
    const SearchLevel level = points_level(padded, s.points);
    const SearchResult e = search_exhaustive(s.lat, level);
    for (bool intervals : {false, true}) {
      BranchAndBoundOptions bo;
      bo.heading_intervals = intervals;
      const HeadingGrids grids(s.lat, level);
      const SearchResult b = search_branch_and_bound(s.lat, grids, pyramid, bo);
      expect_pose(b.best, e.best, s.what);
      expect_leaves_exact(b, e, s.lat, s.what);
    }
  }
}

// The estimator with the field model: bnb and exhaustive agree on the sonar ring (floats)
// and on a laser scan (fixed point), and the estimate's fit and confidence stay in [0, 1].
TEST(LikelihoodFieldSearch, EstimatorBnbEqualsExhaustiveOnSonarAndScans) {
  const SonarRing ring = load_sonar_ring(ring_path());
  for (const char* name : {"room_rect", "room_furnished"}) {
    const OccupancyMap map = load_ros_map(map_path(name));
    CorrelationOptions exhaustive, bnb;
    exhaustive.global = bnb.global = GlobalModel::LikelihoodField;
    exhaustive.strategy = SearchStrategy::Exhaustive;
    exhaustive.hypotheses = bnb.hypotheses = 3;
    exhaustive.reach_m = bnb.reach_m = 4.0;
    const CorrelationEstimator a(map, ring, exhaustive), b(map, ring, bnb);
    Rng rng(5);
    for (int t = 0; t < 6; ++t) {
      const Pose2 truth = sample_free_pose(map, ring, 0.25, rng);
      Observation obs;
      if (t % 2 == 0) {
        obs.ranges = simulate_sonar(map, ring, truth, SonarSimOptions::realistic(rng.next()));
      } else {
        obs.scan = simulate_scan(map, truth, 90, 4.0, 0.01, rng.next());
      }
      SearchWindow w;
      w.center = {truth.x + 0.3, truth.y - 0.2, truth.theta + 0.2};
      const Estimate ea = a.estimate(obs, w), eb = b.estimate(obs, w);
      const std::string what = std::string(name) + " trial " + std::to_string(t);
      EXPECT_EQ(ea.lattice_pose.x, eb.lattice_pose.x) << what;
      EXPECT_EQ(ea.lattice_pose.y, eb.lattice_pose.y) << what;
      EXPECT_EQ(ea.lattice_pose.theta, eb.lattice_pose.theta) << what;
      EXPECT_EQ(ea.score, eb.score) << what;
      EXPECT_EQ(ea.second_score, eb.second_score) << what;
      for (const Estimate* e : {&ea, &eb}) {
        EXPECT_GE(e->normalized_score, 0.0) << what;
        EXPECT_LE(e->normalized_score, 1.0) << what;
        EXPECT_GE(e->confidence, 0.0) << what;
        EXPECT_LE(e->confidence, 1.0) << what;
        EXPECT_TRUE(e->covariance.allFinite()) << what;
      }
      EXPECT_LT(std::hypot(eb.pose.x - truth.x, eb.pose.y - truth.y), 0.15) << what;
    }
  }
}

TEST(LikelihoodFieldSearch, BadFieldOptionsAreRefusedByTheEstimator) {
  const OccupancyMap map = load_ros_map(map_path("room_rect"));
  CorrelationOptions o;
  o.global = GlobalModel::LikelihoodField;
  o.field.sigma_m = -1.0;
  expect_error([&] { CorrelationEstimator(map, load_sonar_ring(ring_path()), o); },
               {"sigma_m", "-1"});
}

}  // namespace
}  // namespace gridloc
