// Tests of sensors/src/sonar_sim.cpp: the cone ray-casting sonar simulator (seed 001 §4).
#include "gridloc/sensors/sonar_sim.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/rng.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

// room_rect: origin (-0.5, -0.5), 0.5 m unknown margin and 0.15 m walls, so the interior
// spans x in [0.15, 6.15] m and y in [0.15, 4.65] m (checked against the map below).
constexpr double kWest = 0.15, kEast = 6.15, kSouth = 0.15, kNorth = 4.65;
constexpr double kCell = 0.05;
// Bundled ring: sonar 5 is mounted at (0, +0.35) looking left (+90 deg), sonar 12 at
// (0, -0.35) looking right (-90 deg).
constexpr int kLeft = 5, kRight = 12;

class SonarSim : public ::testing::Test {
 protected:
  OccupancyMap map = load_ros_map(test::map_path("room_rect"));
  SonarRing ring = load_sonar_ring(test::ring_path());

  CellState at_world(double x, double y) const {
    const Pose2 g = map.geometry.to_grid_frame({x, y, 0.0});
    const Cell c = map.geometry.cell_of(g.x, g.y);
    return map.at(c.ix, c.iy);
  }
};

TEST_F(SonarSim, InteriorBoundsMatchTheMap) {
  EXPECT_EQ(at_world(kWest - 0.5 * kCell, 2.0), CellState::Occupied);
  EXPECT_EQ(at_world(kWest + 0.5 * kCell, 2.0), CellState::Free);
  EXPECT_EQ(at_world(kEast + 0.5 * kCell, 3.0), CellState::Occupied);
  EXPECT_EQ(at_world(kEast - 0.5 * kCell, 3.0), CellState::Free);
  EXPECT_EQ(at_world(3.0, kSouth - 0.5 * kCell), CellState::Occupied);
  EXPECT_EQ(at_world(3.0, kSouth + 0.5 * kCell), CellState::Free);
  EXPECT_EQ(at_world(3.0, kNorth + 0.5 * kCell), CellState::Occupied);
  EXPECT_EQ(at_world(3.0, kNorth - 0.5 * kCell), CellState::Free);
}

TEST_F(SonarSim, NoiseFreeReadingsMatchWallDistances) {
  {
    // Robot at (3, 2) facing east: the left sonar at (3, 2.35) faces the north wall, the
    // right one at (3, 1.65) the south wall.
    const auto r = simulate_sonar(map, ring, {3.0, 2.0, 0.0});
    ASSERT_EQ(r.size(), 14u);
    EXPECT_NEAR(r[kLeft], kNorth - 2.35, kCell);
    EXPECT_NEAR(r[kRight], 1.65 - kSouth, kCell);
  }
  {
    // Robot at (3, 3) facing north: the left sonar at (2.65, 3) faces the west wall, the
    // right one at (3.35, 3) the east wall.
    const auto r = simulate_sonar(map, ring, {3.0, 3.0, std::numbers::pi / 2});
    EXPECT_NEAR(r[kLeft], 2.65 - kWest, kCell);
    EXPECT_NEAR(r[kRight], kEast - 3.35, kCell);
  }
  {
    // Robot at (3, 2.4) facing west: the front sonars (mounted at x = +0.55, y = +-0.10,
    // looking +-10 deg) face the west wall; their shortest ray is the one at 0 deg, which
    // lies inside the 12 deg cone only if |10 deg| < 6 deg -- it does not, so the shortest
    // ray is the cone edge at 4 deg: distance = (x_mount - west) / cos(4 deg).
    const auto r = simulate_sonar(map, ring, {3.0, 2.4, std::numbers::pi});
    const double expected = (3.0 - 0.55 - kWest) / std::cos(deg2rad(4.0));
    EXPECT_NEAR(r[1], expected, kCell);
    EXPECT_NEAR(r[2], expected, kCell);
  }
}

TEST_F(SonarSim, ReadingsLieInTheSonarRange) {
  Rng rng(3);
  for (int i = 0; i < 20; ++i) {
    const Pose2 p{rng.uniform(0.8, 5.5), rng.uniform(0.8, 4.0), rng.uniform(-3.0, 3.0)};
    for (double d : simulate_sonar(map, ring, p, SonarSimOptions::realistic(i))) {
      EXPECT_GE(d, 0.15);
      EXPECT_LE(d, 6.0);
    }
  }
}

TEST_F(SonarSim, Deterministic) {
  const Pose2 p{2.2, 1.7, 0.8};
  const auto a = simulate_sonar(map, ring, p, SonarSimOptions::realistic(7));
  const auto b = simulate_sonar(map, ring, p, SonarSimOptions::realistic(7));
  EXPECT_EQ(a, b);
  const auto c = simulate_sonar(map, ring, p, SonarSimOptions::realistic(8));
  EXPECT_NE(a, c);
  // Without noise the seed does not matter.
  SonarSimOptions quiet1, quiet2;
  quiet1.seed = 1;
  quiet2.seed = 99;
  EXPECT_EQ(simulate_sonar(map, ring, p, quiet1), simulate_sonar(map, ring, p, quiet2));
}

TEST_F(SonarSim, FullDropoutHearsNothing) {
  SonarSimOptions o;
  o.dropout_prob = 1.0;
  const auto r = simulate_sonar(map, ring, {3.0, 2.0, 0.3}, o);
  ASSERT_EQ(r.size(), 14u);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r[i], ring.sonars[i].max_range) << i;
}

TEST_F(SonarSim, FullCrosstalkGivesShortEchoes) {
  SonarSimOptions o;
  o.crosstalk_prob = 1.0;
  const Pose2 p{3.0, 2.0, 0.3};
  const auto clean = simulate_sonar(map, ring, p);
  const auto r = simulate_sonar(map, ring, p, o);
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_GE(r[i], 0.15) << i;
    EXPECT_LE(r[i], clean[i]) << i;
  }
}

TEST_F(SonarSim, MapYawIsHonoured) {
  // The same grid placed in the world with another origin and a 90 deg yaw, and the robot
  // moved with it, hears the same ranges.
  OccupancyMap turned = map;
  turned.geometry.origin = {10.0, -3.0};
  turned.geometry.yaw = std::numbers::pi / 2;
  for (const Pose2 p : {Pose2{3.0, 2.0, 0.0}, Pose2{1.3, 3.1, 2.0}, Pose2{4.4, 1.2, -0.7}}) {
    const Pose2 moved = turned.geometry.to_world_frame(map.geometry.to_grid_frame(p));
    const auto a = simulate_sonar(map, ring, p);
    const auto b = simulate_sonar(turned, ring, moved);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9) << i;
  }
}

TEST_F(SonarSim, BadInput) {
  test::expect_error([&] { simulate_sonar(map, ring, {-5.0, -5.0, 0.0}); }, {"outside the map"});
  test::expect_error([&] { simulate_sonar(map, ring, {100.0, 2.0, 0.0}); }, {"outside the map"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  test::expect_error([&] { simulate_sonar(map, ring, {nan, 2.0, 0.0}); }, {"finite"});
  SonarSimOptions o;
  o.dropout_prob = 1.5;
  test::expect_error([&] { simulate_sonar(map, ring, {3.0, 2.0, 0.0}, o); }, {"probabilit"});
  o = {};
  o.range_sigma_m = -0.1;
  test::expect_error([&] { simulate_sonar(map, ring, {3.0, 2.0, 0.0}, o); }, {"sigma"});
  o = {};
  o.ray_step_deg = 0.0;
  test::expect_error([&] { simulate_sonar(map, ring, {3.0, 2.0, 0.0}, o); }, {"ray_step_deg"});
}

}  // namespace
}  // namespace gridloc
