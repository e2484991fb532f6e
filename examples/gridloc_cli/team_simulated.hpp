#pragma once
// gridloc team --poses: the team simulated at its true poses by the team protocol's
// TeamSimulator (evaluation/team_protocol.hpp), and its answer judged against the truth. The
// measured path (--robots) is team_io.hpp's; cmd_team.cpp reaches the simulation through a
// TeamSimulation, so that it builds against gridloc::engine alone.
#include <cstdint>
#include <functional>
#include <vector>

#include "gridloc/engine/team/team_sensing.hpp"

namespace gridloc::cli {

/// What gridloc team --poses calls: the simulation of a team and the judge of its answer.
struct TeamSimulation {
  std::function<TeamCase(TeamCandidates, const std::vector<Pose2>&, std::uint64_t)> simulate;
  std::function<bool(const TeamAnswer&, const std::vector<Pose2>&)> correct;
};

/// The team protocol's (team_simulated.cpp, linked with gridloc::evaluation): simulated_team
/// and simulated_team_correct.
TeamSimulation team_protocol_simulation();

/// Each robot's sensing simulated at `poses` (noise from `seed`) and turned into candidates
/// by `candidates`, and the links the team can measure.
TeamCase simulated_team(TeamCandidates candidates, const std::vector<Pose2>& poses,
                        std::uint64_t seed);

/// Whether the answer puts every robot within the team protocol's default tolerances of its
/// truth.
bool simulated_team_correct(const TeamAnswer& answer, const std::vector<Pose2>& truth);

}  // namespace gridloc::cli
