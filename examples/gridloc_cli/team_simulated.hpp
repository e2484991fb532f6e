#pragma once
// gridloc team --poses: the team simulated at its true poses by the team protocol's
// TeamSimulator (evaluation/team_protocol.hpp), and its answer judged against the truth. The
// measured path (--robots) is team_io.hpp's.
#include <cstdint>
#include <vector>

#include "gridloc/engine/team/team_sensing.hpp"

namespace gridloc::cli {

/// Each robot's sensing simulated at `poses` (noise from `seed`) and turned into candidates
/// by `candidates`, and the links the team can measure.
TeamCase simulated_team(TeamCandidates candidates, const std::vector<Pose2>& poses,
                        std::uint64_t seed);

/// Whether the answer puts every robot within the team protocol's default tolerances of its
/// truth.
bool simulated_team_correct(const TeamAnswer& answer, const std::vector<Pose2>& truth);

}  // namespace gridloc::cli
