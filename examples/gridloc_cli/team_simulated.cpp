#include "team_simulated.hpp"

#include "gridloc/engine/evaluation/team_protocol.hpp"

namespace gridloc::cli {

TeamCase simulated_team(TeamCandidates candidates, const std::vector<Pose2>& poses,
                        std::uint64_t seed) {
  return TeamSimulator(std::move(candidates)).simulate(poses, seed);
}

bool simulated_team_correct(const TeamAnswer& answer, const std::vector<Pose2>& truth) {
  return judge(answer, truth, TeamProtocolOptions{}).correct;
}

TeamSimulation team_protocol_simulation() {
  return {simulated_team, simulated_team_correct};
}

}  // namespace gridloc::cli
