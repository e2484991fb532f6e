// gridloc disambiguate and eval --protocol disambiguation end to end (issue 15).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace gridloc::test {
namespace {

const std::string kThreeRooms = std::string(GRIDLOC_TEST_MAPS_DIR) + "/polygons/three_rooms.yaml";

TEST(DisambiguateCli, DrivesOutOfTheMiddleRoomUntilOnlyTheTruthRemains) {
  TempDir dir;
  const CliRun run =
      run_cli(dir, "disambiguate --map " + quote(kThreeRooms) +
                       " --pose 5.5,1.5,0 --points 40 --json --out " + quote(dir.file("out")));
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json plan = nlohmann::json::parse(run.out);
  ASSERT_EQ(plan["hypotheses"].size(), 3u);
  EXPECT_EQ(plan["true_hypothesis"], 1);
  EXPECT_TRUE(plan["resolved"]);
  EXPECT_TRUE(plan["true_hypothesis_survived"]);
  EXPECT_EQ(plan["remaining"], nlohmann::json::array({1}));
  EXPECT_GE(plan["stops"].get<int>(), 1);
  EXPECT_EQ(plan["eliminated"].size(), plan["stops"].get<std::size_t>());
  EXPECT_GE(plan["path_length_m"].get<double>(), plan["lower_bound_m"].get<double>() - 0.05);
  EXPECT_GE(plan["path"].size(), 2u);
  EXPECT_EQ(plan["path"][0]["x"], 0.0);
  // The path under the true hypothesis starts at the true start.
  ASSERT_EQ(plan["path_world"].size(), 1u);
  EXPECT_NEAR(plan["path_world"][0]["path"][0]["x"].get<double>(), 5.5, 1e-9);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/disambiguation.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/disambiguation.json")));
}

TEST(DisambiguateCli, AUniqueStartNeedsNoStop) {
  TempDir dir;
  // In the corridor beside its west end wall: no other place looks the same.
  const CliRun run =
      run_cli(dir, "disambiguate --map " + quote(kThreeRooms) + " --pose 0.5,4.0,0 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json plan = nlohmann::json::parse(run.out);
  EXPECT_EQ(plan["hypotheses"].size(), 1u);
  EXPECT_TRUE(plan["resolved"]);
  EXPECT_EQ(plan["stops"], 0);
  EXPECT_EQ(plan["path_length_m"], 0.0);
}

TEST(DisambiguateCli, BadInputGetsOneLineNamingIt) {
  TempDir dir;
  const std::string map = " --map " + quote(kThreeRooms);
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 3.5,1.5,0"), "outside");
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 5.5,1.5,0 --range 0"), "--range");
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 5.5,1.5,0 --range nan"), "--range");
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 5.5,1.5,0 --range -1"), "--range");
  // Nothing but a wall within 0.5 m of the room's centre: no vertex pins the hypotheses.
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 5.5,1.5,0 --range 0.5"),
                   "no map vertex");
  expect_cli_error(run_cli(dir, "disambiguate" + map), "--pose");
  expect_cli_error(
      run_cli(dir, "disambiguate --map " + quote(dir.file("missing.yaml")) + " --pose 1,1,0"),
      "missing.yaml");
  expect_cli_error(run_cli(dir, "disambiguate" + map + " --pose 5.5,1.5,0 --algorithm abc"),
                   "--algorithm");
}

const std::string kSymmetricRoom = std::string(GRIDLOC_TEST_MAPS_DIR) + "/room_symmetric.yaml";

TEST(DisambiguateCli, OnAnOccupancyMapTheEngineKeepsTheTwinItCannotTellApart) {
  TempDir dir;
  const CliRun run = run_cli(dir, "disambiguate --map " + quote(kSymmetricRoom) +
                                      " --pose 1.1,1.76,1.29 --points 40 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json plan = nlohmann::json::parse(run.out);
  EXPECT_EQ(plan["hypotheses"].size(), 2u);  // the pose and its twin turned by 180 degrees
  EXPECT_FALSE(plan["resolved"]);
  EXPECT_TRUE(plan["true_hypothesis_survived"]);
  EXPECT_EQ(plan["remaining"].size(), 2u);
}

TEST(DisambiguateCli, FromReadingsItAnswersWhereToDriveFirst) {
  TempDir dir;
  const std::string readings = dir.file("r.json");
  ASSERT_EQ(run_cli(dir, "simulate --map " + quote(kSymmetricRoom) +
                             " --pose 1.1,1.76,1.29 --out " + quote(readings))
                .status,
            0);
  const CliRun run = run_cli(dir, "disambiguate --map " + quote(kSymmetricRoom) + " --readings " +
                                      quote(readings) + " --points 40 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json plan = nlohmann::json::parse(run.out);
  EXPECT_EQ(plan["hypotheses"].size(), 2u);
  EXPECT_TRUE(plan["true_hypothesis_survived"].is_null());  // nobody knows the truth here
  EXPECT_LE(plan["stops"].get<int>(), 1);
  EXPECT_FALSE(plan["resolved"]);
  expect_cli_error(run_cli(dir, "disambiguate --map " + quote(kSymmetricRoom) + " --readings " +
                                    quote(readings) + " --range 2"),
                   "--range");
  expect_cli_error(
      run_cli(dir, "disambiguate --map " + quote(kThreeRooms) + " --readings " + quote(readings)),
      "--pose");
}

TEST(DisambiguateCli, TheProtocolRunsOnASmallSet) {
  TempDir dir;
  const CliRun run = run_cli(
      dir,
      "eval --protocol disambiguation --environments 1 --starts 1 --repeats 1 --points 5,40 "
      "--range inf,2 --algorithms col,ual --strategies hybrid --json --quiet");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json result = nlohmann::json::parse(run.out);
  EXPECT_EQ(result["trials"], 1);
  ASSERT_EQ(result["configurations"].size(), 8u);  // 2 ranges x 2 algorithms x 2 point counts
  for (const nlohmann::json& row : result["configurations"]) {
    EXPECT_EQ(row["resolved_rate"], 1.0) << row.dump();
    EXPECT_GE(row["mean_path_length"].get<double>(), row["mean_lower_bound"].get<double>() - 0.05);
  }
  EXPECT_TRUE(result["configurations"][0]["range"].is_null());  // unlimited
  EXPECT_EQ(result["configurations"][4]["range"], 2.0);
}

}  // namespace
}  // namespace gridloc::test
