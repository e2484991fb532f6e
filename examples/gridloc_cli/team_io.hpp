#pragma once
// gridloc team's inputs and outputs: the team from true poses (--poses, simulated) or from a
// robots.json of real scans and measured links, and the answer as JSON.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gridloc/engine/team/team_sensing.hpp"

namespace gridloc::cli {

/// The team's world from a polygon map file (features exact) or a map_server YAML.
TeamWorld load_team_world(const std::string& path, const std::string& option = "--map");

/// "x,y,theta;x,y,theta[;...]" (m, m, rad); throws gridloc::Error naming the robot.
std::vector<Pose2> parse_team_poses(const std::string& text);

/// "SIGMA_M[,BEARING_DEG]": the camera's length sigma at its range and its bearing sigma.
void parse_link_noise(const std::string& text, CameraModel& camera);

/// A team read from robots.json (relative scan paths from its folder):
///   {"robots": [{"scan": "r1.csv"} | {"scan": [[angle_rad, range_m], ...]} |
///               {"readings": "sonar.txt"}, ...],
///    "links": [{"from": 0, "to": 1, "length_m": 0.8, "bearing_deg": 30,
///               "back_bearing_deg": -150 (optional)}, ...]}
/// Scans are read as the team's sensor reads them (IR: load_ir_scan_csv's units and
/// clamping; laser: load_scan_csv). Throws gridloc::Error naming the file and the entry.
TeamCase load_team(const std::string& path, const TeamCandidates& candidates);

/// The answer: robots (pose, verdict, candidates, features), solutions, unique, links_used,
/// verdict, swaps, and with a truth each robot's error (the command adds whether it is
/// correct, team_simulated.hpp).
nlohmann::json team_json(const TeamCase& team, const TeamAnswer& answer);

}  // namespace gridloc::cli
