#pragma once
// gridloc disambiguate --pose on an occupancy map: the chair simulated through the whole plan
// (noisy sensing and odometry, the engine in the loop; evaluation/engine_loop.hpp) beside the
// noise-free plan. The robot-facing path (--readings, --scan) is disambiguate_grid.cpp's.
#include <nlohmann/json.hpp>

#include "disambiguate_common.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc::cli {

/// The simulated run as JSON; without --json also its summary on standard output.
nlohmann::json simulated_run_on_grid(const OccupancyMap& map, const SonarRing& ring,
                                     const DisambiguateArgs& args);

}  // namespace gridloc::cli
