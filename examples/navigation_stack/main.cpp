// A wheelchair navigation stack's use of gridloc: the map and the sonar ring are loaded once
// at start-up, one estimator is built once (it precomputes the global grids), and then every
// switch to autonomous mode asks it for a pose from a standstill sonar reading and a rough
// prior. Simulated readings stand in for the sonar driver.
//
//   navigation_stack <map.yaml> <ring.yaml>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/free_pose.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/sonar_ring.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace {

constexpr int kLocalizations = 6;
constexpr std::uint64_t kSeed = 2024;    // fixed, so every run prints the same lines
constexpr double kClearance = 0.25;      // m of free space around the footprint at a test pose
constexpr double kPriorXy = 0.5;         // m: how far off odometry may be after a manual drive
constexpr double kPriorThetaDeg = 30.0;  // deg

// Stands in for the sonar driver: one reading per sonar, in ring order, with realistic noise.
std::vector<double> read_sonars(const gridloc::OccupancyMap& map, const gridloc::SonarRing& ring,
                                const gridloc::Pose2& truth, std::uint64_t seed) {
  return gridloc::simulate_sonar(map, ring, truth, gridloc::SonarSimOptions::realistic(seed));
}

// Stands in for odometry: the true pose off by up to kPriorXy in any direction and
// kPriorThetaDeg in heading.
gridloc::Pose2 rough_prior(const gridloc::Pose2& truth, gridloc::Rng& rng) {
  const double distance = kPriorXy * std::sqrt(rng.uniform());  // uniform over the disc
  const double direction = rng.uniform(-std::numbers::pi, std::numbers::pi);
  const double dtheta = gridloc::deg2rad(rng.uniform(-kPriorThetaDeg, kPriorThetaDeg));
  return {truth.x + distance * std::cos(direction), truth.y + distance * std::sin(direction),
          gridloc::normalize_angle(truth.theta + dtheta)};
}

int run(const char* map_path, const char* ring_path) {
  // Once at start-up: loading and the global-grid pyramid are the expensive part.
  const gridloc::OccupancyMap map = gridloc::load_ros_map(map_path);
  const gridloc::SonarRing ring = gridloc::load_sonar_ring(ring_path);
  const gridloc::CorrelationEstimator estimator(map, ring);
  std::printf("navigation_stack: map %s, ring '%s' (%zu sonars)\n", map_path, ring.name.c_str(),
              ring.sonars.size());

  gridloc::Rng rng(kSeed);
  for (int i = 0; i < kLocalizations; ++i) {
    const gridloc::Pose2 truth = gridloc::sample_free_pose(map, ring, kClearance, rng);
    const gridloc::Observation observation{read_sonars(map, ring, truth, rng.next())};

    // The default window (+-0.8 m, +-45 deg) covers the prior's error; its translation step
    // must be the estimator's finest cell.
    gridloc::SearchWindow window;
    window.center = rough_prior(truth, rng);
    window.step_xy = estimator.options().resolution;

    const gridloc::Estimate e = estimator.estimate(observation, window);
    const double error_m = std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
    const double error_deg =
        gridloc::rad2deg(std::abs(gridloc::normalize_angle(e.pose.theta - truth.theta)));
    std::printf(
        "localization %d: truth (%6.3f, %6.3f, %7.2f deg)  estimate (%6.3f, %6.3f, %7.2f deg)  "
        "error %.3f m %5.2f deg  confidence %.2f  %.1f ms\n",
        i + 1, truth.x, truth.y, gridloc::rad2deg(truth.theta), e.pose.x, e.pose.y,
        gridloc::rad2deg(e.pose.theta), error_m, error_deg, e.confidence, e.stats.elapsed_ms);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <map.yaml> <ring.yaml>\n",
                 argc > 0 ? argv[0] : "navigation_stack");
    return 2;
  }
  try {
    return run(argv[1], argv[2]);
  } catch (const gridloc::Error& e) {
    // Bad map, ring or reading: the library's message names the file and field.
    std::fprintf(stderr, "navigation_stack: %s\n", e.what());
    return 2;
  }
}
