// gridloc team and eval --protocol team end to end (seed 003: team localization through
// virtual links, Rynn 2003 ch. V and VI).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"
#include "gridloc/engine/team/virtual_link.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/rotating_ir.hpp"

namespace gridloc::test {
namespace {

const std::string kMaps = std::string(GRIDLOC_TEST_MAPS_DIR) + "/polygons/";
const std::string kTRoom = kMaps + "t_room.yaml";
const std::string kTRoomLab = kMaps + "t_room_lab.yaml";

// Ch. V case 2: two robots whose views and link fit the T room's mirror image as well.
const std::string kCase2Poses = "1.3,0.2,2.748893572;0.15,3.25,0.7853981634";
const std::string kCase2Sensing = " --ir-range 0.5 --link-range 4 --exact --json";

// Ch. VI: the two robots of the lab experiment, in the bar of the T, facing west.
const Pose2 kLabRobot0{0.65, 0.85, 3.14159265}, kLabRobot1{0.1, 0.1, 3.14159265};
const std::string kLabPoses = "0.65,0.85,3.14159265;0.1,0.1,3.14159265";

nlohmann::json run_json(const TempDir& dir, const std::string& args) {
  const CliRun run = run_cli(dir, args);
  EXPECT_EQ(run.status, 0) << run.err;
  if (run.status != 0) return nlohmann::json::object();
  return nlohmann::json::parse(run.out);
}

void expect_robot_fields(const nlohmann::json& robot) {
  EXPECT_TRUE(robot.contains("pose")) << robot.dump();
  EXPECT_TRUE(robot["verdict"].is_string()) << robot.dump();
  ASSERT_TRUE(robot["candidates"].is_array()) << robot.dump();
  EXPECT_FALSE(robot["candidates"].empty());
  for (const nlohmann::json& candidate : robot["candidates"]) {
    EXPECT_TRUE(candidate["pose"].contains("x")) << candidate.dump();
    EXPECT_TRUE(candidate["weight"].is_number()) << candidate.dump();
  }
}

TEST(TeamCli, TwoRobotsInTheTRoomHaveTwoMirroredSolutions) {
  TempDir dir;
  const nlohmann::json team = run_json(
      dir, "team --map " + quote(kTRoom) + " --poses " + quote(kCase2Poses) + kCase2Sensing);
  EXPECT_EQ(team["unique"], false);
  EXPECT_EQ(team["verdict"], "ambiguous");
  EXPECT_EQ(team["solutions"].size(), 2u);
  ASSERT_EQ(team["robots"].size(), 2u);
  for (const nlohmann::json& robot : team["robots"]) {
    expect_robot_fields(robot);
    EXPECT_EQ(robot["verdict"], "ambiguous");
    EXPECT_EQ(robot["places"].size(), 2u);
    EXPECT_TRUE(robot.contains("true_pose"));
    EXPECT_TRUE(robot["error_m"].is_number());
  }
  ASSERT_EQ(team["links_used"].size(), 1u);
  const nlohmann::json& link = team["links_used"][0];
  EXPECT_EQ(link["from"], 0);
  EXPECT_EQ(link["to"], 1);
  EXPECT_NEAR(link["length_m"].get<double>(), 3.2596, 1e-3);  // exact: the true distance
  EXPECT_TRUE(link["bearing_deg"].is_number());
}

TEST(TeamCli, AThirdRobotBreaksTheMirror) {
  TempDir dir;
  const nlohmann::json team =
      run_json(dir, "team --map " + quote(kTRoom) + " --poses " +
                        quote(kCase2Poses + ";1.4,2.4,1.570796327") + kCase2Sensing);
  EXPECT_EQ(team["unique"], true);
  EXPECT_EQ(team["correct"], true);
  EXPECT_EQ(team["solutions"].size(), 1u);
  ASSERT_EQ(team["robots"].size(), 3u);
  for (const nlohmann::json& robot : team["robots"]) {
    expect_robot_fields(robot);
    EXPECT_LE(robot["error_m"].get<double>(), 0.03) << robot.dump();
  }
}

TEST(TeamCli, TheLabExperimentLocalizesBothRobotsAndWritesItsPicture) {
  TempDir dir;
  const nlohmann::json team =
      run_json(dir, "team --map " + quote(kTRoomLab) + " --poses " + quote(kLabPoses) +
                        " --json --out " + quote(dir.file("out")));
  EXPECT_EQ(team["unique"], true);
  EXPECT_EQ(team["correct"], true);
  ASSERT_EQ(team["robots"].size(), 2u);
  for (const nlohmann::json& robot : team["robots"]) {
    expect_robot_fields(robot);
    EXPECT_EQ(robot["verdict"], "localized");
    EXPECT_LE(robot["error_m"].get<double>(), 0.02) << robot.dump();
    EXPECT_LE(robot["error_deg"].get<double>(), 1.5) << robot.dump();
  }
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/team.png")));
  const nlohmann::json written = nlohmann::json::parse(read_file(dir.file("out/team.json")));
  EXPECT_EQ(written["unique"], team["unique"]);
}

/// A raw scan of the lab robot (noisy, seed 1; not smoothed: the tool smooths what it reads).
RangeScan lab_scan(const Pose2& pose) {
  IrSensorOptions sensor;
  sensor.smoothing_half_window = 0;
  return simulate_ir_scan(load_polygon_map(kTRoomLab), pose, sensor, 1);
}

std::string scan_csv(const RangeScan& scan) {
  std::string text = "angle_rad,range_m\n";
  char row[64];
  for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
    std::snprintf(row, sizeof row, "%.17g,%.17g\n", scan.angles[k], scan.ranges[k]);
    text += row;
  }
  return text;
}

nlohmann::json scan_rows(const RangeScan& scan) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < scan.ranges.size(); ++k)
    rows.push_back({scan.angles[k], scan.ranges[k]});
  return rows;
}

nlohmann::json link_entry(const VirtualLink& link) {
  return {{"from", link.from},
          {"to", link.to},
          {"length_m", link.length_m},
          {"bearing_deg", link.bearing * 180.0 / 3.14159265358979323846},
          {"back_bearing_deg", link.back_bearing * 180.0 / 3.14159265358979323846}};
}

/// robots.json of the lab pair: robot 0's scan in r0.csv, robot 1's inline, one exact link.
nlohmann::json lab_robots(const TempDir& dir) {
  dir.write("r0.csv", scan_csv(lab_scan(kLabRobot0)));
  const VirtualLink link = measure_link(0, 1, kLabRobot0, kLabRobot1, CameraModel{}, 0);
  return {{"robots", {{{"scan", "r0.csv"}}, {{"scan", scan_rows(lab_scan(kLabRobot1))}}}},
          {"links", {link_entry(link)}}};
}

TEST(TeamCli, MeasuredScansAndLinksFromRobotsJsonLocalizeTheLabPair) {
  TempDir dir;
  const std::string robots = dir.write("robots.json", lab_robots(dir).dump());
  const nlohmann::json team =
      run_json(dir, "team --map " + quote(kTRoomLab) + " --robots " + quote(robots) + " --json");
  EXPECT_EQ(team["unique"], true);
  EXPECT_FALSE(team.contains("correct"));  // nobody knows the truth
  ASSERT_EQ(team["robots"].size(), 2u);
  const Pose2 truth[] = {kLabRobot0, kLabRobot1};
  for (std::size_t r = 0; r < 2; ++r) {
    const nlohmann::json& robot = team["robots"][r];
    expect_robot_fields(robot);
    EXPECT_FALSE(robot.contains("true_pose"));
    EXPECT_FALSE(robot.contains("error_m"));
    EXPECT_NEAR(robot["pose"]["x"].get<double>(), truth[r].x, 0.02) << robot.dump();
    EXPECT_NEAR(robot["pose"]["y"].get<double>(), truth[r].y, 0.02) << robot.dump();
  }
}

TEST(TeamCli, BadTeamsGetOneLineNamingTheFault) {
  TempDir dir;
  const std::string lab = "team --map " + quote(kTRoomLab);
  const nlohmann::json good = lab_robots(dir);
  nlohmann::json far = good;
  far["links"][0]["length_m"] = 1.5;  // the camera measures up to 1.1 m
  expect_cli_error(run_cli(dir, lab + " --robots " + quote(dir.write("far.json", far.dump()))),
                   "beyond the camera's range");
  // 1.38 m apart: beyond the camera, so the two robots measure no link.
  expect_cli_error(run_cli(dir, lab + " --poses " + quote("0.1,0.1,3.14159;1.4,0.6,0")), "no link");
  // Three returns among saturated readings (inline ranges are clamped to the 0.3 m IR range):
  // too few for a wall, so no robot sees a feature.
  nlohmann::json blind = good;
  nlohmann::json rows = nlohmann::json::array();
  for (int k = 0; k < 360; ++k)
    rows.push_back({-3.14159265358979 + k * 0.0174532925199, k < 3 ? 0.2 : 1.0});
  blind["robots"] = {{{"scan", rows}}, {{"scan", rows}}};
  expect_cli_error(run_cli(dir, lab + " --robots " + quote(dir.write("blind.json", blind.dump()))),
                   "no robot has a candidate");
  const std::string good_file = dir.write("good.json", good.dump());
  expect_cli_error(
      run_cli(dir, lab + " --poses " + quote(kLabPoses) + " --robots " + quote(good_file)),
      "either --poses");
  expect_cli_error(run_cli(dir, lab + " --poses 1,2"), "--poses");
  expect_cli_error(run_cli(dir, lab + " --robots " + quote(dir.file("missing.json"))),
                   "missing.json");
  expect_cli_error(run_cli(dir, lab + " --robots " + quote(dir.write("text.json", "robots: 2\n"))),
                   "text.json");
}

TEST(TeamCli, TheProtocolRunsOnASmallSet) {
  TempDir dir;
  const nlohmann::json result = run_json(
      dir, "eval --protocol team --robots 1,2 --trials 3 --maps polygons/t_room --json --quiet");
  EXPECT_EQ(result["protocol"], "team");
  EXPECT_EQ(result["trials"], 3);
  ASSERT_EQ(result["configurations"].size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    const nlohmann::json& row = result["configurations"][c];
    EXPECT_EQ(row["robots"], static_cast<int>(c) + 1);
    for (const char* field : {"unique_correct_rate", "ambiguous_rate", "wrong_localized",
                              "mean_position_error_m", "mean_heading_error_deg", "median_ms"})
      EXPECT_TRUE(row.contains(field)) << field << " in " << row.dump();
  }
  ASSERT_EQ(result["per_map"].size(), 2u);  // one map x two team sizes
  for (const nlohmann::json& row : result["per_map"]) EXPECT_EQ(row["map"], "t_room");
  expect_cli_error(run_cli(dir, "eval --protocol team --sensor ir --robots 0"), "--robots");
}

}  // namespace
}  // namespace gridloc::test
