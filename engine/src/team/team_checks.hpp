#pragma once
// The steps of localize_team after the join: the links left over, the robots' own scans,
// the averaging over all links, duplicates, and the answer.
#include <vector>

#include "gridloc/engine/team/team_localization.hpp"

namespace gridloc::team_detail {

/// Keeps the solutions every link in `checks` agrees with (within its gate and with a line of
/// sight).
std::vector<TeamSolution> agreeing_with_links(std::vector<TeamSolution> solutions,
                                              const std::vector<VirtualLink>& links,
                                              const std::vector<int>& checks,
                                              const MapFeatures& map, const TeamOptions& options);

/// Keeps the solutions that put every robot in the map's free space and whose pose for each
/// robot with a scan agrees with it; a slide is shortened to the stretch where they do.
std::vector<TeamSolution> agreeing_with_scans(std::vector<TeamSolution> solutions,
                                              const std::vector<TeamRobot>& robots,
                                              const MapFeatures& map, const TeamOptions& options);

/// Moves each fixed solution's poses to the weighted fit of the robots' candidates and all the
/// links: positions by least squares, headings averaged with those the back bearings imply.
void refine(std::vector<TeamSolution>& solutions, const std::vector<TeamRobot>& robots,
            const std::vector<VirtualLink>& links, const TeamOptions& options);

/// Weights filled, duplicates merged, best first (weight, then residual), rivals only.
std::vector<TeamSolution> ranked_rivals(std::vector<TeamSolution> solutions,
                                        const std::vector<TeamRobot>& robots,
                                        const TeamOptions& options);

/// The verdicts, each robot's places and the swaps, from the rivals.
TeamAnswer answer_from(std::vector<TeamSolution> rivals, const std::vector<TeamRobot>& robots,
                       const MapFeatures& map, const TeamOptions& options);

}  // namespace gridloc::team_detail
