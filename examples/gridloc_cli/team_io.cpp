#include "team_io.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/readings_io.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {

namespace fs = std::filesystem;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double number_in(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value))
    throw Error(what + ": '" + text + "' is not a finite number");
  return value;
}

}  // namespace

TeamWorld load_team_world(const std::string& path, const std::string& option) {
  if (is_polygon_map_input(path, option)) {
    return make_team_world(load_polygon_map(map_input_path(path, option), limits()));
  }
  return make_team_world(load_ros_map_input(path, option));
}

std::vector<Pose2> parse_team_poses(const std::string& text) {
  std::vector<Pose2> poses;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ';'))
    poses.push_back(parse_pose(item, "--poses robot " + std::to_string(poses.size())));
  if (poses.empty()) throw Error("--poses: give x,y,theta for each robot, separated by ';'");
  return poses;
}

void parse_link_noise(const std::string& text, CameraModel& camera) {
  const auto comma = text.find(',');
  const double length = number_in(text.substr(0, comma), "--link-noise sigma");
  require_flag(length >= 0.0, "--link-noise", length, "length sigma must be >= 0");
  camera.length_sigma_at_max_m = length;
  if (comma == std::string::npos) return;
  const double bearing = number_in(text.substr(comma + 1), "--link-noise bearing");
  require_flag(bearing >= 0.0, "--link-noise", bearing, "bearing sigma must be >= 0");
  camera.bearing_sigma = bearing * kDeg;
}

namespace {

nlohmann::json read_json(const std::string& path) {
  const std::string text = read_input_file(input_path(path, "--robots"), "robots file", limits());
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not JSON (" + std::string(e.what()) + ")");
  }
}

RangeScan inline_scan(const nlohmann::json& rows, const std::string& where, double max_range) {
  RangeScan scan;
  scan.max_range = max_range;
  for (const auto& row : rows) {
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number())
      throw Error(where + ": each scan reading is [angle_rad, range_m]");
    scan.angles.push_back(row[0].get<double>());
    scan.ranges.push_back(std::min(row[1].get<double>(), max_range));
  }
  validate(scan);
  return scan;
}

TeamRobot read_robot(const nlohmann::json& entry, const fs::path& folder, std::size_t index,
                     const TeamCandidates& candidates, TeamCase& team) {
  const std::string where = "robot " + std::to_string(index);
  if (!entry.is_object()) throw Error(where + ": expected an object with a scan or readings");
  const TeamSensing& sensing = candidates.sensing();
  if (sensing.sensor == TeamSensor::Sonar) {
    if (!entry.contains("readings") || !entry["readings"].is_string())
      throw Error(where + ": a sonar team gives each robot's \"readings\" file");
    return candidates.from_sonar(
        load_readings((folder / entry["readings"].get<std::string>()).string(), limits()));
  }
  if (!entry.contains("scan")) throw Error(where + ": missing \"scan\" (a CSV file or rows)");
  const auto& scan_entry = entry["scan"];
  RangeScan scan;
  if (scan_entry.is_string()) {
    const std::string file = (folder / scan_entry.get<std::string>()).string();
    scan = sensing.sensor == TeamSensor::Ir ? load_ir_scan_csv(file, sensing.ir, limits())
                                            : load_scan_csv(file, sensing.laser_range_m, limits());
  } else if (scan_entry.is_array()) {
    scan = inline_scan(
        scan_entry, where,
        sensing.sensor == TeamSensor::Ir ? sensing.ir.max_range_m : sensing.laser_range_m);
    if (sensing.sensor == TeamSensor::Ir)
      scan = smooth_ir_scan(scan, sensing.ir.smoothing_half_window);
  } else {
    throw Error(where + ": \"scan\" is a CSV file name or an array of [angle_rad, range_m]");
  }
  std::vector<ScanFeature> features;
  TeamRobot robot = candidates.from_scan(scan, &features);
  team.scans.push_back(scan);
  team.features.push_back(std::move(features));
  return robot;
}

double angle_field(const nlohmann::json& entry, const std::string& name, const std::string& where,
                   bool required) {
  const std::string deg = name + "_deg";
  if (entry.contains(deg) && entry[deg].is_number()) return entry[deg].get<double>() * kDeg;
  if (entry.contains(name) && entry[name].is_number()) return entry[name].get<double>();
  if (required) throw Error(where + ": missing \"" + deg + "\" (or \"" + name + "\" in rad)");
  return std::nan("");
}

VirtualLink read_link(const nlohmann::json& entry, std::size_t index) {
  const std::string where = "link " + std::to_string(index);
  if (!entry.is_object() || !entry.contains("from") || !entry.contains("to") ||
      !entry["from"].is_number_integer() || !entry["to"].is_number_integer() ||
      !entry.contains("length_m") || !entry["length_m"].is_number())
    throw Error(where + ": expected {\"from\": i, \"to\": j, \"length_m\": d, \"bearing_deg\": a}");
  VirtualLink link;
  link.from = entry["from"].get<int>();
  link.to = entry["to"].get<int>();
  link.length_m = entry["length_m"].get<double>();
  link.bearing = angle_field(entry, "bearing", where, true);
  link.back_bearing = angle_field(entry, "back_bearing", where, false);
  return link;
}

}  // namespace

TeamCase load_team(const std::string& path, const TeamCandidates& candidates) {
  const nlohmann::json root = read_json(path);
  if (!root.is_object() || !root.contains("robots") || !root["robots"].is_array() ||
      root["robots"].empty())
    throw Error(path + ": expected {\"robots\": [...], \"links\": [...]}");
  const fs::path folder = fs::path(path).parent_path();
  TeamCase team;
  try {
    for (std::size_t r = 0; r < root["robots"].size(); ++r)
      team.robots.push_back(read_robot(root["robots"][r], folder, r, candidates, team));
    if (root.contains("links")) {
      if (!root["links"].is_array()) throw Error("\"links\" must be an array");
      for (std::size_t l = 0; l < root["links"].size(); ++l)
        team.links.push_back(read_link(root["links"][l], l));
    }
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return team;
}

namespace {

nlohmann::json candidate_json(const PoseCandidate& candidate,
                              const std::vector<ScanFeature>* features) {
  nlohmann::json out = {{"pose", to_json(candidate.pose)}, {"weight", candidate.weight}};
  if (candidate.segment()) {
    out["along"] = {candidate.along.x(), candidate.along.y()};
    out["length_m"] = candidate.length;
  }
  if (features && candidate.feature >= 0 && candidate.feature < static_cast<int>(features->size()))
    out["feature"] = to_string((*features)[candidate.feature].kind);
  return out;
}

nlohmann::json feature_json(const ScanFeature& feature) {
  return {{"kind", to_string(feature.kind)},
          {"point", {feature.point.x(), feature.point.y()}},
          {"fit_rms_m", feature.fit_rms_m},
          {"points", feature.points}};
}

nlohmann::json robot_json(const TeamCase& team, const TeamAnswer& answer, std::size_t r) {
  const RobotAnswer& robot = answer.robots[r];
  const std::vector<ScanFeature>* features = r < team.features.size() ? &team.features[r] : nullptr;
  nlohmann::json candidates = nlohmann::json::array();
  for (const PoseCandidate& candidate : team.robots[r].candidates)
    candidates.push_back(candidate_json(candidate, features));
  nlohmann::json out = {
      {"pose", answer.solutions.empty() ? nlohmann::json(nullptr) : to_json(robot.pose)},
      {"verdict", to_string(robot.verdict)},
      {"candidates", candidates}};
  nlohmann::json places = nlohmann::json::array();
  for (const Pose2& place : robot.places) places.push_back(to_json(place));
  out["places"] = places;
  out["slides"] = robot.slides;
  if (features) {
    nlohmann::json found = nlohmann::json::array();
    for (const ScanFeature& feature : *features) found.push_back(feature_json(feature));
    out["features"] = found;
  }
  if (r < team.truth.size()) {
    out["true_pose"] = to_json(team.truth[r]);
    if (!answer.solutions.empty()) {
      out["error_m"] = std::hypot(robot.pose.x - team.truth[r].x, robot.pose.y - team.truth[r].y);
      out["error_deg"] = std::abs(normalize_angle(robot.pose.theta - team.truth[r].theta)) / kDeg;
    }
  }
  return out;
}

nlohmann::json solution_json(const TeamSolution& solution) {
  nlohmann::json poses = nlohmann::json::array();
  for (const Pose2& pose : solution.poses) poses.push_back(to_json(pose));
  nlohmann::json out = {{"poses", poses},
                        {"weight", solution.weight},
                        {"residual_m", solution.residual_m},
                        {"slide", nullptr}};
  if (solution.slide.moving())
    out["slide"] = {{"direction", {solution.slide.direction.x(), solution.slide.direction.y()}},
                    {"length_m", solution.slide.length}};
  return out;
}

nlohmann::json link_json(const VirtualLink& link) {
  return {{"from", link.from},
          {"to", link.to},
          {"length_m", link.length_m},
          {"bearing_deg", link.bearing / kDeg},
          {"back_bearing_deg", number_or_null(link.back_bearing / kDeg)}};
}

}  // namespace

nlohmann::json team_json(const TeamCase& team, const TeamAnswer& answer) {
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t r = 0; r < team.robots.size(); ++r)
    robots.push_back(robot_json(team, answer, r));
  nlohmann::json solutions = nlohmann::json::array();
  for (const TeamSolution& solution : answer.solutions)
    solutions.push_back(solution_json(solution));
  nlohmann::json used = nlohmann::json::array();
  for (int l : answer.links_used) used.push_back(link_json(team.links[l]));
  nlohmann::json swaps = nlohmann::json::array();
  for (const auto& [i, j] : answer.swaps) swaps.push_back({i, j});
  nlohmann::json out = {{"robots", robots},
                        {"solutions", solutions},
                        {"unique", answer.unique()},
                        {"verdict", to_string(answer.verdict)},
                        {"links_used", used},
                        {"swaps", swaps},
                        {"truncated", answer.truncated}};
  return out;
}

}  // namespace gridloc::cli
