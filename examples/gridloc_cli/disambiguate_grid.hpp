#pragma once
// gridloc disambiguate on an occupancy map: the engine's global search gives the
// hypotheses; with --pose the chair is simulated through the whole plan (noisy sensing and
// odometry, the engine in the loop), with --readings or --scan (taken at the start) the command
// answers where to drive first.
#include <vector>

#include "disambiguate_common.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc::cli {

/// The hypotheses as the summary lists them.
void print_grid_hypotheses(const std::vector<Pose2>& hypotheses);

struct GridDisambiguationSimulation;  // disambiguate_simulated.hpp

/// Runs it (--pose through `simulation`) and prints JSON (--json) or a summary; --out gets
/// disambiguation.json.
void run_disambiguate_on_grid(const DisambiguateArgs& args,
                              const GridDisambiguationSimulation& simulation);

}  // namespace gridloc::cli
