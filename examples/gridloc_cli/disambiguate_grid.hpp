#pragma once
// gridloc disambiguate on an occupancy map: the engine's global search gives the
// hypotheses; with --pose the chair is simulated through the whole plan (noisy sensing and
// odometry, the engine in the loop), with --readings or --scan (taken at the start) the command
// answers where to drive first.
#include "disambiguate_common.hpp"

namespace gridloc::cli {

/// Runs it and prints JSON (--json) or a summary; --out gets disambiguation.json.
void run_disambiguate_on_grid(const DisambiguateArgs& args);

}  // namespace gridloc::cli
