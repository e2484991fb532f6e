#pragma once
// gridloc disambiguate --pose on an occupancy map: the chair simulated through the whole plan
// (noisy sensing and odometry, the engine in the loop; evaluation/engine_loop.hpp) beside the
// noise-free plan. The robot-facing path (--readings, --scan) is disambiguate_grid.cpp's;
// it reaches the simulation through a GridDisambiguationSimulation, so that it builds against
// gridloc::engine alone.
#include <functional>
#include <nlohmann/json.hpp>

#include "disambiguate_common.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc::cli {

/// What gridloc disambiguate --pose calls on an occupancy map.
struct GridDisambiguationSimulation {
  std::function<nlohmann::json(const OccupancyMap&, const SonarRing&, const DisambiguateArgs&)> run;
};

/// The simulated run as JSON; without --json also its summary on standard output.
nlohmann::json simulated_run_on_grid(const OccupancyMap& map, const SonarRing& ring,
                                     const DisambiguateArgs& args);

/// The engine loop's (disambiguate_simulated.cpp, linked with gridloc::evaluation):
/// simulated_run_on_grid.
GridDisambiguationSimulation engine_loop_simulation();

}  // namespace gridloc::cli
