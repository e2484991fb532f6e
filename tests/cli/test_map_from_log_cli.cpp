// End-to-end tests of `gridloc map-from-log`: a CARMEN log simulated in a known room drawn
// into a map_server map (all scans, the map part, the held-out part), the summary in text and
// JSON, and the one-line error contract.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "cli_support.hpp"
#include "flaser_log.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_cli_error;
using test::quote;
using test::run_cli;
using test::TempDir;

using test::flaser_log;

TEST(MapFromLogCli, DrawsAllScansIntoAMapServerMap) {
  TempDir dir;
  const std::string log = dir.write("room.log", flaser_log(40, 2.0));
  const std::string out = dir.file("room_map.yaml");
  const auto r =
      run_cli(dir, "map-from-log --log " + quote(log) + " --out " + quote(out) + " --json --png");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scans"], 40);
  EXPECT_EQ(j["scans_used"], 40);
  EXPECT_EQ(j["part"], "all");
  EXPECT_EQ(j["split"]["rule"], "all");
  EXPECT_EQ(j["files"]["yaml"], out);
  EXPECT_EQ(j["files"]["pgm"], dir.file("room_map.pgm"));
  EXPECT_TRUE(std::filesystem::exists(dir.file("room_map.png")));
  const OccupancyMap map = load_ros_map(out);
  EXPECT_EQ(j["map"]["width"], map.width());
  EXPECT_EQ(j["map"]["height"], map.height());
  EXPECT_EQ(j["map"]["resolution"], 0.05);
  // The room (6 m x 4 m) plus the 1 m margin, give or take a cell.
  EXPECT_NEAR(j["map"]["width_m"].get<double>(), 8.0, 0.15);
  EXPECT_NEAR(j["map"]["height_m"].get<double>(), 6.0, 0.15);
  std::size_t occupied = 0, free = 0;
  for (const CellState s : map.cells) {
    occupied += s == CellState::Occupied;
    free += s == CellState::Free;
  }
  EXPECT_EQ(j["cells"]["occupied"], occupied);
  EXPECT_EQ(j["cells"]["free"], free);
  EXPECT_GT(occupied, 250u);  // most of the 400 wall cells
  EXPECT_GT(free, 7000u);     // most of the 9000 floor cells
}

// A file output is named after what it holds (--map-out, simulate's --readings-out); --out,
// a folder in the other commands, is their old spelling and writes the same files.
TEST(MapFromLogCli, FileOutputsHaveTheirOwnNamesAndTheOldOutStillWorks) {
  TempDir dir;
  const std::string log = dir.write("room.log", flaser_log(20, 2.0));
  const std::string by_name = dir.file("new.yaml"), by_out = dir.file("old.yaml");
  ASSERT_EQ(
      run_cli(dir, "map-from-log --log " + quote(log) + " --map-out " + quote(by_name)).status, 0);
  ASSERT_EQ(run_cli(dir, "map-from-log --log " + quote(log) + " --out " + quote(by_out)).status, 0);
  EXPECT_EQ(test::read_file(dir.file("new.pgm")), test::read_file(dir.file("old.pgm")));
  const test::CliRun help = run_cli(dir, "map-from-log --help");
  EXPECT_NE(help.out.find("--map-out"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("  --out"), std::string::npos) << help.out;

  const std::string map = test::maps_dir() + "/room_rect.yaml";
  const std::string readings = dir.file("r.json"), old_readings = dir.file("old.json");
  const std::string simulate = "simulate --map " + quote(map) + " --ring " +
                               quote(test::maps_dir() + "/sensors/wheelchair_14.yaml") +
                               " --pose 1,1,0 ";
  ASSERT_EQ(run_cli(dir, simulate + "--readings-out " + quote(readings)).status, 0);
  ASSERT_EQ(run_cli(dir, simulate + "--out " + quote(old_readings)).status, 0);
  EXPECT_FALSE(test::read_file(readings).empty());
  EXPECT_EQ(test::read_file(readings), test::read_file(old_readings));
}

TEST(MapFromLogCli, TheMapAndHeldOutPartsAlternate) {
  TempDir dir;
  // 40 scans 2 s apart: 30 s blocks of 15, 15 and 10 scans.
  const std::string log = dir.write("room.log", flaser_log(40, 2.0));
  const auto part = [&](const std::string& name, const std::string& extra) {
    const auto r =
        run_cli(dir, "map-from-log --log " + quote(log) + " --out " +
                         quote(dir.file(name + ".yaml")) + " --json --part " + name + extra);
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto map = part("map", ""), held_out = part("held-out", "");
  EXPECT_EQ(map["split"]["rule"], "time blocks");
  EXPECT_EQ(map["split"]["blocks"], 3);
  EXPECT_EQ(map["scans_used"], 25);
  EXPECT_EQ(held_out["scans_used"], 15);
  EXPECT_EQ(map["split"]["held_out_scans"], 15);
  EXPECT_EQ(map["split"]["timestamps_unusable"], "");
  // Blocks of 10 s, then by count when the times cannot cut them.
  EXPECT_EQ(part("map", " --block-s 10")["scans_used"], 20);
  const std::string still = dir.write("still.log", flaser_log(40, 0.0));
  const auto r = run_cli(dir, "map-from-log --log " + quote(still) + " --out " +
                                  quote(dir.file("s.yaml")) + " --part held-out --block-scans 8");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto l = test::lines(r.out);
  ASSERT_EQ(l.size(), 3u) << r.out;
  EXPECT_NE(l[0].find("16 of 40 scans (part held-out, split: scan blocks (5 blocks; map part 24, "
                      "held-out part 16 scans))"),
            std::string::npos)
      << l[0];
  EXPECT_NE(l[1].find("timestamps not used: the timestamps span 0 s"), std::string::npos) << l[1];
  EXPECT_NE(l[2].find("cells ("), std::string::npos) << l[2];
  EXPECT_NE(l[2].find("occupied"), std::string::npos) << l[2];
}

TEST(MapFromLogCli, ErrorsAreOneLine) {
  TempDir dir;
  const std::string log = dir.write("room.log", flaser_log(20, 2.0));
  const std::string out = " --out " + quote(dir.file("m.yaml"));
  const auto run = [&](const std::string& args) { return run_cli(dir, "map-from-log " + args); };
  expect_cli_error(run("--log " + quote(dir.file("none.log")) + out), {"none.log", "not found"});
  expect_cli_error(run("--log " + quote(log)), "--out");
  expect_cli_error(run("--log " + quote(log) + out + " --part odd"), "--part");
  expect_cli_error(run("--log " + quote(log) + out + " --resolution 0"), "resolution");
  expect_cli_error(run("--log " + quote(log) + out + " --resolution 0.0001"),
                   {"map from log", "cells exceeds the limit", "--max-cells"});
  expect_cli_error(run("--log " + quote(log) + out + " --max-range -1"), "max_range_m");
  expect_cli_error(run("--log " + quote(log) + out + " --block-s -3 --part map"), "block_s");
  expect_cli_error(run("--log " + quote(log) + out + " --block-scans 0"), "block_scans");
  expect_cli_error(run("--log " + quote(log) + out + " --occupied-ratio 2"), "occupied_ratio");
  // One block holds the 20 scans (38 s): by time, or by count had the times been unusable.
  expect_cli_error(
      run("--log " + quote(log) + out + " --part held-out --block-s 100 --block-scans 100"),
      {"held-out part holds no scan"});
  const std::string empty = dir.write("empty.log", "PARAM x 1 nohost 0\n");
  expect_cli_error(run("--log " + quote(empty) + out), "no laser scan");
  const std::string bad = dir.write("bad.log.gz", std::string("\x1f\x8b\x08\x00garbage", 11));
  expect_cli_error(run("--log " + quote(bad) + out), {"bad.log.gz", "gzip"});
  expect_cli_error(run("--log " + quote(log) + " --out " + quote(dir.file("no/such/m.yaml"))),
                   "cannot write");
}

}  // namespace
}  // namespace gridloc
