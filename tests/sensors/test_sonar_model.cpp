// Tests of sensors/src/sonar_model.cpp: the oriented cone model of seed 001 §3 and the
// paper's "turned" baseline.
#include "gridloc/sensors/sonar_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kRes = 0.1;

SonarRing one_sonar(double bearing = 0.0, double radius = 0.0, double heading = 0.0) {
  SonarRing ring;
  ring.name = "one";
  SonarSpec s;
  s.bearing = bearing;
  s.radius = radius;
  s.heading = heading;
  s.cone = deg2rad(12.0);
  s.min_range = 0.15;
  s.max_range = 6.0;
  ring.sonars.push_back(s);
  return ring;
}

double positive_sum(const SparseLocalGrid& g) {
  double s = 0.0;
  for (float v : g.value) s += v > 0.0f ? v : 0.0;
  return s;
}
double negative_sum(const SparseLocalGrid& g) {
  double s = 0.0;
  for (float v : g.value) s += v < 0.0f ? v : 0.0;
  return s;
}

using CellSet = std::set<std::pair<int, int>>;

CellSet positive_cells(const SparseLocalGrid& g) {
  CellSet cells;
  for (std::size_t k = 0; k < g.size(); ++k) {
    if (g.value[k] > 0.0f) cells.insert({g.dx[k], g.dy[k]});
  }
  return cells;
}

/// Checks that `cells` form a simple 8-connected chain: connected, every cell has at most
/// two 8-neighbours in the set, and there are exactly n - 1 neighbouring pairs (no cycle,
/// in particular no redundant corner cell of a 4-connected step, which would form a
/// triangle with its two neighbours).
::testing::AssertionResult is_simple_8_chain(const CellSet& cells) {
  if (cells.empty()) return ::testing::AssertionFailure() << "no arc cells";
  std::size_t pairs = 0;
  for (const auto& [x, y] : cells) {
    int neighbours = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx || dy) && cells.count({x + dx, y + dy})) ++neighbours;
      }
    }
    if (neighbours > 2) {
      return ::testing::AssertionFailure()
             << "arc cell (" << x << ", " << y << ") has " << neighbours << " arc neighbours";
    }
    pairs += static_cast<std::size_t>(neighbours);
  }
  pairs /= 2;
  // Connectivity by flood fill.
  CellSet seen = {*cells.begin()};
  std::vector<std::pair<int, int>> stack = {*cells.begin()};
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const std::pair<int, int> n{x + dx, y + dy};
        if (cells.count(n) && seen.insert(n).second) stack.push_back(n);
      }
    }
  }
  if (seen.size() != cells.size()) {
    return ::testing::AssertionFailure()
           << "arc is not 8-connected: " << seen.size() << " of " << cells.size() << " reached";
  }
  if (pairs != cells.size() - 1) {
    return ::testing::AssertionFailure() << "arc of " << cells.size() << " cells has " << pairs
                                         << " neighbouring pairs (redundant cells)";
  }
  return ::testing::AssertionSuccess();
}

TEST(SonarModel, OneEchoSharesPlusOneOnTheArcAndMinusOneBeforeIt) {
  for (double theta_deg : {0.0, 17.0, 90.0, 135.0, -100.0, 180.0}) {
    const auto ring = one_sonar(deg2rad(-10.3), 0.559, deg2rad(-10.0));
    const SparseLocalGrid g = rasterize_oriented(ring, {2.0}, deg2rad(theta_deg), kRes);
    EXPECT_NEAR(positive_sum(g), 1.0, 1e-4) << theta_deg;
    EXPECT_NEAR(negative_sum(g), -1.0, 1e-4) << theta_deg;
    EXPECT_EQ(g.resolution, kRes);
    EXPECT_EQ(g.theta, deg2rad(theta_deg));
    // All positive cells share the same value 1/n1, all negative ones -1/n2.
    std::set<float> pos, neg;
    for (float v : g.value) (v > 0 ? pos : neg).insert(v);
    EXPECT_EQ(pos.size(), 1u) << theta_deg;
    EXPECT_EQ(neg.size(), 1u) << theta_deg;
  }
}

TEST(SonarModel, NoEchoGivesFreeSpaceOnly) {
  const auto ring = one_sonar();
  for (double theta_deg : {0.0, 33.0, -120.0}) {
    const SparseLocalGrid g = rasterize_oriented(ring, {6.0}, deg2rad(theta_deg), kRes);
    EXPECT_EQ(positive_cells(g).size(), 0u);
    EXPECT_NEAR(negative_sum(g), -1.0, 1e-4);
    // The free sector reaches the max range.
    int far = 0;
    for (std::size_t k = 0; k < g.size(); ++k)
      far = std::max(far, std::abs(g.dx[k]) + std::abs(g.dy[k]));
    EXPECT_GE(far, 55);
  }
}

TEST(SonarModel, CellsLieInsideTheCone) {
  const auto ring = one_sonar();
  const double d = 3.0;
  const SparseLocalGrid g = rasterize_oriented(ring, {d}, 0.0, kRes);
  const double slack = std::sqrt(0.5) * kRes + 1e-9;  // half a cell diagonal
  const double depth = SonarModelOptions{}.arc_depth_cells * kRes;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double x = g.dx[k] * kRes, y = g.dy[k] * kRes;
    const double r = std::hypot(x, y);
    EXPECT_LE(r, d + depth + slack) << g.dx[k] << "," << g.dy[k];
    // Lateral offset within the 6 deg half-aperture (plus half a cell diagonal).
    EXPECT_LE(std::abs(y), x * std::tan(deg2rad(6.0)) + slack) << g.dx[k] << "," << g.dy[k];
    if (g.value[k] > 0.0f) {
      EXPECT_NEAR(r, d, depth + slack) << g.dx[k] << "," << g.dy[k];
    }
  }
}

TEST(SonarModel, ArcDepthWidensTheArcButKeepsItsMass) {
  const auto ring = one_sonar();
  const SonarModelOptions paper{0.0};
  for (double d : {1.0, 2.5, 4.0}) {
    const SparseLocalGrid thin =
        rasterize_oriented(ring, {d}, 0.3, kRes, Eigen::Vector2d::Zero(), paper);
    const SparseLocalGrid deep = rasterize_oriented(ring, {d}, 0.3, kRes);
    const auto thin_arc = positive_cells(thin), deep_arc = positive_cells(deep);
    EXPECT_GT(deep_arc.size(), thin_arc.size()) << d;
    double sum = 0.0;
    for (float v : deep.value) sum += v > 0.0f ? v : 0.0f;
    EXPECT_NEAR(sum, 1.0, 1e-4) << d;
  }
}

TEST(SonarModel, ArcIsASimpleEightConnectedChain) {
  const auto straight = one_sonar();
  const auto mounted = one_sonar(deg2rad(28.61), 0.6265, deg2rad(30.0));
  for (const SonarRing* ring : {&straight, &mounted}) {
    for (double d : {0.5, 1.0, 2.0, 3.7, 5.5}) {
      for (int theta_deg = -180; theta_deg < 180; theta_deg += 7) {
        // Seed 001's one-cell arc (arc depth 0).
        const SparseLocalGrid g = rasterize_oriented(
            *ring, {d}, deg2rad(theta_deg), kRes, Eigen::Vector2d::Zero(), SonarModelOptions{0.0});
        EXPECT_TRUE(is_simple_8_chain(positive_cells(g)))
            << "range " << d << " theta " << theta_deg << " radius " << ring->sonars[0].radius;
      }
    }
  }
}

TEST(SonarModel, ArcIsASimpleChainAtFinerResolution) {
  const auto ring = one_sonar();
  for (double d : {0.8, 2.0, 4.5}) {
    for (int theta_deg = 0; theta_deg < 90; theta_deg += 11) {
      const SparseLocalGrid g = rasterize_oriented(ring, {d}, deg2rad(theta_deg), 0.05,
                                                   Eigen::Vector2d::Zero(), SonarModelOptions{0.0});
      EXPECT_TRUE(is_simple_8_chain(positive_cells(g))) << d << " " << theta_deg;
    }
  }
}

TEST(SonarModel, CellsAreSortedByRowThenColumnWithoutDuplicates) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  const std::vector<double> r = {2.3, 2.1, 2.6, 6.0, 2.3, 2.3, 1.7,
                                 2.5, 2.3, 2.3, 6.0, 1.5, 1.5, 1.5};
  for (LocalModel model : {LocalModel::Oriented, LocalModel::Turned}) {
    const SparseLocalGrid g = rasterize(ring, r, deg2rad(40.0), kRes, model);
    ASSERT_EQ(g.dx.size(), g.size());
    ASSERT_EQ(g.dy.size(), g.size());
    for (std::size_t k = 1; k < g.size(); ++k) {
      EXPECT_LT(std::make_pair(g.dy[k - 1], g.dx[k - 1]), std::make_pair(g.dy[k], g.dx[k]));
    }
  }
}

TEST(SonarModel, RotatingTheRobotEqualsRotatingTheMount) {
  // The model is oriented before it is discretized: a sonar at heading h on a robot at
  // theta gives exactly the grid of a sonar at heading h + theta on a robot at 0.
  for (double t : {0.3, 1.2, -2.5}) {
    const auto a = rasterize_oriented(one_sonar(0.4, 0.5, 0.1), {2.5}, t, kRes);
    const auto b = rasterize_oriented(one_sonar(0.4 + t, 0.5, 0.1 + t), {2.5}, 0.0, kRes);
    EXPECT_EQ(a.dx, b.dx) << t;
    EXPECT_EQ(a.dy, b.dy) << t;
    EXPECT_EQ(a.value, b.value) << t;
  }
}

class RingModel : public ::testing::Test {
 protected:
  SonarRing ring = load_sonar_ring(test::ring_path());
  SonarRing bare = [this] {
    SonarRing r = ring;
    r.footprint.polygon.clear();
    return r;
  }();
  // Simulated-looking readings: 12 echoes, two sonars without echo.
  std::vector<double> ranges = {2.30, 2.11, 2.61, 2.85, 2.33, 2.30, 1.71,
                                2.52, 6.0,  2.31, 2.52, 1.52, 1.50, 6.0};
  int echoes = 12;
};

TEST_F(RingModel, FootprintCellsShareMinusN) {
  for (const std::vector<double>& r : {std::vector<double>(14, 6.0), ranges}) {
    for (double theta_deg : {0.0, 30.0, 90.0, 135.0, -71.0}) {
      const double t = deg2rad(theta_deg);
      const SparseLocalGrid with = rasterize_oriented(ring, r, t, kRes);
      const SparseLocalGrid without = rasterize_oriented(bare, r, t, kRes);
      // The footprint (1.10 x 0.70 m rectangle) in cells, computed here independently.
      auto in_footprint = [&](int dx, int dy) {
        const double x = dx * kRes, y = dy * kRes;
        const double fx = std::cos(t) * x + std::sin(t) * y;
        const double fy = -std::sin(t) * x + std::cos(t) * y;
        return std::abs(fx) < 0.55 && std::abs(fy) < 0.35;
      };
      std::map<std::pair<int, int>, float> rest;
      for (std::size_t k = 0; k < without.size(); ++k) {
        if (!in_footprint(without.dx[k], without.dy[k])) {
          rest[{without.dx[k], without.dy[k]}] = without.value[k];
        }
      }
      double fp_sum = 0.0;
      int fp_cells = 0;
      std::set<float> fp_values;
      std::map<std::pair<int, int>, float> with_rest;
      for (std::size_t k = 0; k < with.size(); ++k) {
        if (in_footprint(with.dx[k], with.dy[k])) {
          fp_sum += with.value[k];
          ++fp_cells;
          fp_values.insert(with.value[k]);
        } else {
          with_rest[{with.dx[k], with.dy[k]}] = with.value[k];
        }
      }
      EXPECT_NEAR(fp_sum, -14.0, 1e-3) << theta_deg;
      EXPECT_EQ(fp_values.size(), 1u) << theta_deg;
      if (theta_deg == 0.0) {
        EXPECT_EQ(fp_cells, 11 * 7);
      }
      // Outside the footprint the grid is untouched.
      EXPECT_EQ(with_rest, rest) << theta_deg;
    }
  }
}

TEST_F(RingModel, OrientedEqualsTurnedAtThetaZero) {
  const SparseLocalGrid o = rasterize_oriented(ring, ranges, 0.0, kRes);
  const SparseLocalGrid t = rasterize_turned(ring, ranges, 0.0, kRes);
  EXPECT_EQ(o.dx, t.dx);
  EXPECT_EQ(o.dy, t.dy);
  EXPECT_EQ(o.value, t.value);
  const SparseLocalGrid d = rasterize(ring, ranges, 0.0, kRes, LocalModel::Turned);
  EXPECT_EQ(d.value, t.value);
}

TEST_F(RingModel, OrientedKeepsOnePerEchoTurnedDoesNot) {
  // Oriented: arc values of several cones add, so the positive mass is exactly one per echo
  // at every heading. Turned: moving cells by a rotation loses and doubles cells.
  double turned_deviation = 0.0;
  for (int theta_deg = -180; theta_deg < 180; theta_deg += 15) {
    const double t = deg2rad(theta_deg);
    const SparseLocalGrid o = rasterize_oriented(ring, ranges, t, kRes);
    EXPECT_NEAR(positive_sum(o), echoes, 1e-3) << theta_deg;
    const SparseLocalGrid tu = rasterize_turned(ring, ranges, t, kRes);
    turned_deviation += std::abs(positive_sum(tu) - echoes);
  }
  EXPECT_GT(turned_deviation, 0.1);

  const double t135 = deg2rad(135.0);
  const SparseLocalGrid o = rasterize_oriented(ring, ranges, t135, kRes);
  const SparseLocalGrid tu = rasterize_turned(ring, ranges, t135, kRes);
  EXPECT_NE(o.value, tu.value);
  EXPECT_GT(std::abs(positive_sum(tu) - echoes), std::abs(positive_sum(o) - echoes));
  // Rounding rotated cell centres merges cells: the turned grid has fewer cells than the
  // upright one it was made from.
  EXPECT_LT(tu.size(), rasterize_oriented(ring, ranges, 0.0, kRes).size());
}

TEST_F(RingModel, ExtentAndMass) {
  const SparseLocalGrid g = rasterize_oriented(ring, std::vector<double>(14, 6.0), 0.0, kRes);
  EXPECT_LE(g.extent(), static_cast<int>(std::ceil(ring.reach() / kRes)) + 1);
  EXPECT_GE(g.extent(), 60);
  // No echo: each of the 14 cones gives -1 in free space, the footprint -14 (overlaps of
  // free sectors add, so the total is exact up to cells the footprint overrides).
  EXPECT_LE(g.mass(), 28.0 + 1e-3);
  EXPECT_GT(g.mass(), 14.0);
}

TEST(SonarModelErrors, NonPositiveResolution) {
  const auto ring = one_sonar();
  for (double r : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN()}) {
    test::expect_error([&] { rasterize_oriented(ring, {2.0}, 0.0, r); }, {"resolution"});
    test::expect_error([&] { rasterize(ring, {2.0}, 0.0, r, LocalModel::Turned); }, {"resolution"});
  }
}

TEST(SonarModelErrors, NonFiniteOrFarCentre) {
  const auto ring = one_sonar();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& centre : {Eigen::Vector2d(nan, 0.0), Eigen::Vector2d(0.0, inf)}) {
    for (LocalModel model : {LocalModel::Oriented, LocalModel::Turned}) {
      test::expect_error([&] { rasterize(ring, {2.0}, 0.0, kRes, model, centre); },
                         {"local grid centre", "finite"});
    }
  }
  test::expect_error(
      [&] {
        rasterize(ring, {2.0}, 0.0, kRes, LocalModel::Oriented, {1e300, 0.0});
      },
      {"canvas", "46339"});
}

}  // namespace
}  // namespace gridloc
