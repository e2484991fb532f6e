// End-to-end tests of the gridloc command-line tool (examples/gridloc_cli): simulate ->
// localize round trip, the help and docs, and the one-line error contract (stderr, exit
// code 2). eval's protocols: test_eval_cli.cpp; visibility sectors: test_sectors_cli.cpp.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "cli_support.hpp"
#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::TempDir;

using test::CliRun;
using test::expect_cli_error;
using test::lines;
using test::quote;
using test::read_file;
using test::run_cli;

using Cli = test::CliTest;
using test::write_scan_csv;

TEST_F(Cli, SimulateThenLocalize) {
  // The pose of the example must be free for the whole chair footprint.
  const OccupancyMap m = load_ros_map(map);
  const SonarRing sonar_ring = load_sonar_ring(ring);
  const Pose2 pose{1.0, 1.0, 0.0};
  for (double fx = -0.55; fx <= 0.55 + 1e-9; fx += 0.05) {
    for (double fy = -0.35; fy <= 0.35 + 1e-9; fy += 0.05) {
      const Pose2 g = m.geometry.to_grid_frame({pose.x + fx, pose.y + fy, 0.0});
      const Cell c = m.geometry.cell_of(g.x, g.y);
      ASSERT_TRUE(m.geometry.contains(c.ix, c.iy));
      ASSERT_EQ(m.at(c.ix, c.iy), CellState::Free) << fx << "," << fy;
    }
  }

  const std::string readings = dir.file("readings.json");
  const CliRun sim = run_cli(dir, "simulate --map " + quote(map) + " --ring " + quote(ring) +
                                      " --pose 1,1,0 --out " + quote(readings));
  ASSERT_EQ(sim.status, 0) << sim.err;
  EXPECT_EQ(sim.out, "");
  const auto written = nlohmann::json::parse(read_file(readings));
  // The file holds exactly what the library simulates (doubles round-trip through JSON).
  EXPECT_EQ(written.at("ranges_m").get<std::vector<double>>(), simulate_sonar(m, sonar_ring, pose));
  EXPECT_EQ(written.at("pose").at("x").get<double>(), 1.0);

  const CliRun loc = run_cli(dir, "localize --map " + quote(map) + " --ring " + quote(ring) +
                                      " --readings " + quote(readings) + " --prior 1.2,0.9,0.2");
  ASSERT_EQ(loc.status, 0) << loc.err;
  EXPECT_EQ(loc.err, "");
  const auto j = nlohmann::json::parse(loc.out);
  const double x = j.at("pose").at("x"), y = j.at("pose").at("y"), t = j.at("pose").at("theta");
  EXPECT_LE(std::hypot(x - 1.0, y - 1.0), 0.10) << loc.out;
  EXPECT_LE(std::abs(rad2deg(normalize_angle(t))), 7.0) << loc.out;
  EXPECT_NEAR(j.at("theta_deg").get<double>(), rad2deg(t), 1e-9);
  for (const char* key :
       {"score", "normalized_score", "confidence", "alternatives", "stats", "timing"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  // The default strategy is the fastest exact one, branch and bound: one level, proven.
  EXPECT_EQ(j.at("stats").at("levels").get<int>(), 1);
  EXPECT_TRUE(j.at("stats").at("proven_optimal").get<bool>());
  EXPECT_EQ(j.at("stats").at("upper_bound").get<double>(), j.at("score").get<double>());
}

TEST_F(Cli, SimulateToStdout) {
  const CliRun r = run_cli(dir, "simulate --map " + quote(map) + " --pose 3,2,0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("ranges_m").size(), 14u);
}

// simulate --scan writes the CSV localize --scan reads: a reader without a scanner can run
// the README's --scan examples.
TEST_F(Cli, SimulateAScanThenLocalizeIt) {
  const std::string scan = dir.file("scan.csv");
  const CliRun sim =
      run_cli(dir, "simulate --map " + quote(map) +
                       " --pose 1,1,0.4 --scan --beams 180 --max-range 8 --out " + quote(scan));
  ASSERT_EQ(sim.status, 0) << sim.err;
  const CliRun loc = run_cli(dir, "localize --map " + quote(map) + " --scan " + quote(scan) +
                                      " --max-range 8 --prior 1.2,0.9,0.3");
  ASSERT_EQ(loc.status, 0) << loc.err;
  const auto j = nlohmann::json::parse(loc.out);
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - 1.0,
                       j.at("pose").at("y").get<double>() - 1.0),
            0.10)
      << loc.out;
  EXPECT_LE(std::abs(rad2deg(normalize_angle(j.at("pose").at("theta").get<double>() - 0.4))), 2.0)
      << loc.out;
  const CliRun bad =
      run_cli(dir, "simulate --map " + quote(map) + " --pose 1,1,0 --scan --beams 0");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("--beams must lie in [1, 100000], got 0"), std::string::npos) << bad.err;
}

// `-` reads the readings or the scan from standard input; its errors name standard input.
TEST_F(Cli, ReadingsAndScansFromStandardInput) {
  const std::string readings = dir.file("r.json"), scan = dir.file("s.csv");
  ASSERT_EQ(run_cli(dir, "simulate --map " + quote(map) + " --pose 1,1,0 --out " + quote(readings))
                .status,
            0);
  const CliRun from_file = run_cli(dir, "localize --map " + quote(map) + " --readings " +
                                            quote(readings) + " --prior 1.2,0.9,0.2");
  const CliRun piped = run_cli(dir, "localize --map " + quote(map) +
                                        " --readings - --prior 1.2,0.9,0.2 < " + quote(readings));
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(nlohmann::json::parse(piped.out).at("pose"),
            nlohmann::json::parse(from_file.out).at("pose"));
  dir.write("s.csv", "0,1\nnot,a number\n");
  expect_cli_error(
      run_cli(dir, "localize --map " + quote(map) + " --scan - --prior 1,1,0 < " + quote(scan)),
      {"standard input:2:"});
}

TEST_F(Cli, MissingMapFile) {
  const std::string missing = dir.file("no_such_map.yaml");
  const std::string readings =
      dir.write("r.json", R"({"ranges_m": [2,2,2,2,2,2,2,2,2,2,2,2,2,2]})");
  expect_cli_error(run_cli(dir, "localize --map " + quote(missing) + " --readings " +
                                    quote(readings) + " --prior 1,1,0"),
                   missing);
  expect_cli_error(run_cli(dir, "simulate --map " + quote(missing) + " --pose 1,1,0"), missing);
}

TEST_F(Cli, MalformedPrior) {
  const std::string readings =
      dir.write("r.json", R"({"ranges_m": [2,2,2,2,2,2,2,2,2,2,2,2,2,2]})");
  for (const std::string prior : {"1,2", "1,a,0", "1,2,3,4", "x"}) {
    expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " +
                                      quote(readings) + " --prior " + quote(prior)),
                     "--prior");
  }
}

TEST_F(Cli, ReadingsCountMismatch) {
  const std::string readings = dir.write("r.json", R"({"ranges_m": [2,2,2,2,2,2,2,2,2,2,2,2,2]})");
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings) +
                                    " --prior 3,2,0"),
                   "expected 14");
}

TEST_F(Cli, MissingReadingsFileAndOption) {
  const std::string missing = dir.file("none.json");
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(missing) +
                                    " --prior 3,2,0"),
                   missing);
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --prior 3,2,0"), "--readings");
}

TEST_F(Cli, BadStrategyAndSubcommand) {
  const std::string readings =
      dir.write("r.json", R"({"ranges_m": [2,2,2,2,2,2,2,2,2,2,2,2,2,2]})");
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings) +
                                    " --prior 3,2,0 --strategy fastest"),
                   "fastest");
  const CliRun r = run_cli(dir, "teleport");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("gridloc: error: unknown command 'teleport'; the commands are: localize, "
                        "simulate, demo,",
                        0),
            0u)
      << r.err;
  const CliRun none = run_cli(dir, "--max-file-mb 10");
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("no command given; the commands are: localize,"), std::string::npos)
      << none.err;
  // A missing option of a command is still named as such.
  const CliRun option = run_cli(dir, "simulate --pose 1,1,0");
  EXPECT_NE(option.err.find("--map is required"), std::string::npos) << option.err;
}

// Progress on a pipe or a log file: whole lines, no carriage returns (those are for a
// terminal only).
TEST_F(Cli, ProgressWithoutATerminalIsWholeLines) {
  const CliRun r = run_cli(dir, "eval --trials 2 --maps " + quote(map));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[eval] 2/2 poses (1 maps x 2 trials"), std::string::npos) << r.err;
}

// Every option each command's --help lists is documented: in the README, the CLI
// reference, the maps' README or a family's doc page.
TEST_F(Cli, EveryHelpOptionIsDocumented) {
  const std::string root = test::maps_dir() + "/..";
  std::string docs = read_file(root + "/README.md") +
                     read_file(root + "/examples/gridloc_cli/README.md") +
                     read_file(root + "/maps/README.md");
  for (const auto& page : std::filesystem::directory_iterator(root + "/engine/doc")) {
    docs += read_file(page.path().string());
  }
  for (const char* command :
       {"localize", "simulate", "demo", "eval", "eval sonar", "eval laser", "eval drive",
        "eval sectors", "eval disambiguation", "eval team", "relations", "map-from-log", "hallway",
        "heatmap", "sectors", "disambiguate", "team", "track", "merge"}) {
    const CliRun help = run_cli(dir, std::string(command) + " --help");
    ASSERT_EQ(help.status, 0) << command;
    for (const std::string& line : lines(help.out)) {
      // An option's own line starts with two spaces and its name (descriptions wrap deeper).
      if (line.rfind("  --", 0) != 0) continue;
      const auto end = line.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-", 4);
      const std::string option = line.substr(2, end - 2);
      if (option == "--help") continue;
      bool found = false;
      for (auto at = docs.find(option); at != std::string::npos && !found;
           at = docs.find(option, at + 1)) {
        const char next = at + option.size() < docs.size() ? docs[at + option.size()] : ' ';
        found = !(std::isalnum(static_cast<unsigned char>(next)) || next == '-');
      }
      EXPECT_TRUE(found) << command << " " << option << " is in --help but in no doc";
    }
  }
}

TEST_F(Cli, VersionIsPrinted) {
  const CliRun r = run_cli(dir, "--version");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("gridloc ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find('.'), std::string::npos) << r.out;
}

TEST_F(Cli, BadSearchOptionsAreNamed) {
  const std::string readings =
      dir.write("r.json", R"({"ranges_m": [2,2,2,2,2,2,2,2,2,2,2,2,2,2]})");
  const std::string base =
      "localize --map " + quote(map) + " --readings " + quote(readings) + " --prior 3,2,0";
  // room_rect is 7 x 5.5 m with its walls: a +-50 m window is larger than the map.
  expect_cli_error(run_cli(dir, base + " --window-xy 50"), "larger than the map");
  expect_cli_error(run_cli(dir, base + " --budget-ms -1"), "--budget-ms");
  expect_cli_error(run_cli(dir, base + " --budget-ms 5 --strategy multires"),
                   "--budget-ms needs --strategy bnb");
  expect_cli_error(run_cli(dir, base + " --scan-model beams"), "--scan-model");
  expect_cli_error(run_cli(dir, base + " --free-samples 0"), "--free-samples");
  expect_cli_error(run_cli(dir, base + " --ring-quantization-share -1"),
                   "--ring-quantization-share");
  expect_cli_error(run_cli(dir, base + " --scan-quantization-share 1.5"),
                   "--scan-quantization-share");
  expect_cli_error(run_cli(dir, base + " --rising-edge-check maybe"), "--rising-edge-check");
}

TEST_F(Cli, ScanModelsAndMultiresReportWhatTheyProve) {
  // A 90-beam scan cast by hand in room_rect (6 x 4.5 m inside) from (3, 2) in the room's
  // own frame, heading 0: the nearest of the walls and the two boxes against them (desk,
  // cupboard) along each beam. maps/generate_maps.py puts the room's corner at world
  // (0.15, 0.15) (map origin -0.5 plus 0.5 m margin and 0.15 m wall), so the truth is (3.15, 2.15).
  struct Box {
    double x0, y0, x1, y1;
  };
  const Box boxes[] = {{0.5, 3.8, 1.9, 4.5}, {5.5, 0.6, 6.0, 1.8}};
  std::string csv = "# angle_rad,range_m\n";
  for (int k = 0; k < 90; ++k) {
    const double a = -std::numbers::pi + k * 2.0 * std::numbers::pi / 90;
    const double c = std::cos(a), s = std::sin(a);
    double r = 100.0;
    if (c > 1e-9) r = std::min(r, 3.0 / c);
    if (c < -1e-9) r = std::min(r, -3.0 / c);
    if (s > 1e-9) r = std::min(r, 2.5 / s);
    if (s < -1e-9) r = std::min(r, -2.0 / s);
    for (const Box& b : boxes) {  // slab test of the ray from (3, 2)
      double t0 = 0.0, t1 = 100.0;
      for (const auto& [o, d, lo, hi] : {std::tuple{3.0, c, b.x0, b.x1}, {2.0, s, b.y0, b.y1}}) {
        if (std::abs(d) < 1e-12) {
          if (o < lo || o > hi) t0 = 1e9;
          continue;
        }
        const double ta = (lo - o) / d, tb = (hi - o) / d;
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      if (t0 <= t1) r = std::min(r, t0);
    }
    csv += std::to_string(a) + "," + std::to_string(r) + "\n";
  }
  const std::string scan = dir.write("room.csv", csv);
  for (const std::string model : {"samples", "rays", "hits"}) {
    const CliRun r = run_cli(dir, "localize --map " + quote(map) + " --scan " + quote(scan) +
                                      " --prior 3.35,2.0,0.1 --scan-model " + model);
    ASSERT_EQ(r.status, 0) << model << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const double x = j.at("pose").at("x"), y = j.at("pose").at("y");
    EXPECT_LE(std::hypot(x - 3.15, y - 2.15), 0.05) << model << ": " << r.out;
    EXPECT_TRUE(j.at("stats").at("proven_optimal").get<bool>()) << model;
  }
  const CliRun m = run_cli(dir, "localize --map " + quote(map) + " --scan " + quote(scan) +
                                    " --prior 3.35,2.0,0.1 --strategy multires --json");
  ASSERT_EQ(m.status, 0) << m.err;
  const auto j = nlohmann::json::parse(m.out);
  EXPECT_FALSE(j.at("stats").at("proven_optimal").get<bool>());  // a heuristic proves nothing
  EXPECT_TRUE(j.at("stats").at("upper_bound").is_null());
}

TEST_F(Cli, GlobalLocalizationWithoutPrior) {
  const std::string readings = dir.file("readings.json");
  ASSERT_EQ(run_cli(dir, "simulate --map " + quote(map) + " --pose 1,1,0 --out " + quote(readings))
                .status,
            0);
  const CliRun r = run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings) +
                                    " --global --strategy bnb");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double x = j.at("pose").at("x"), y = j.at("pose").at("y"), t = j.at("pose").at("theta");
  EXPECT_LE(std::hypot(x - 1.0, y - 1.0), 0.10) << r.out;
  EXPECT_LE(std::abs(rad2deg(normalize_angle(t))), 7.0) << r.out;
  // The lattice winner and the window searched are reported beside the refined pose.
  EXPECT_TRUE(j.at("lattice").contains("pose"));
  EXPECT_NEAR(j.at("window").at("half_theta").get<double>(), std::numbers::pi, 1e-12);

  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings) +
                                    " --global --prior 1,1,0"),
                   "--global");
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings)),
                   "--prior");
  const std::string scan = dir.write("s.csv", "0.0,1.0\n");
  expect_cli_error(run_cli(dir, "localize --map " + quote(map) + " --readings " + quote(readings) +
                                    " --scan " + quote(scan) + " --prior 1,1,0"),
                   "--scan");
}

TEST_F(Cli, AScansDefaultLatticeFollowsTheMapAndTheScan) {
  // On the 5 cm apartment map, without --step-xy / --step-theta: the map's cell and the
  // heading step that moves the farthest return by half a cell, not seed 001's 10 cm x 5 deg.
  const std::string map_file = test::map_path("apartment_small");
  const OccupancyMap m = load_ros_map(map_file);
  const Pose2 truth{6.5, 4.5, -2.0};
  const std::string scan =
      write_scan_csv(dir, "apartment.csv", simulate_scan(m, truth, 360, 8.0, 0.01, 3));
  const CliRun r = run_cli(dir, "localize --map " + quote(map_file) + " --scan " + quote(scan) +
                                    " --prior 6.8,4.2,-1.7");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double lattice_x = j.at("lattice").at("pose").at("x");
  EXPECT_NEAR(std::remainder(lattice_x - 0.025 + 0.5, 0.05), 0.0, 1e-6) << r.out;  // cell centre
  // The truth lies on a cell corner, the lattice's worst case: 2.5 cm off along each axis.
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - truth.x,
                       j.at("pose").at("y").get<double>() - truth.y),
            0.04)
      << r.out;
  EXPECT_LE(std::abs(normalize_angle(j.at("pose").at("theta").get<double>() - truth.theta)),
            deg2rad(0.3))
      << r.out;
  // Given steps are kept: seed 001's lattice lands on 10 cm cells.
  const CliRun coarse = run_cli(dir, "localize --map " + quote(map_file) + " --scan " +
                                         quote(scan) + " --prior 6.8,4.2,-1.7 --step-xy 0.1");
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  const double coarse_x = nlohmann::json::parse(coarse.out).at("lattice").at("pose").at("x");
  EXPECT_NEAR(std::remainder(coarse_x - 0.05 + 0.5, 0.1), 0.0, 1e-6) << coarse.out;
}

TEST_F(Cli, LocalizeWithIcpOnALaserScan) {
  // A 360-beam scan simulated on the small apartment, written as angle,range lines.
  const std::string map_file = test::map_path("apartment_small");
  const OccupancyMap m = load_ros_map(map_file);
  const Pose2 truth{6.5, 4.5, -2.0};
  const std::string scan =
      write_scan_csv(dir, "apartment.csv", simulate_scan(m, truth, 360, 8.0, 0.01, 3));
  for (const std::string estimator : {"icp", "correlation+icp"}) {
    const CliRun r = run_cli(dir, "localize --map " + quote(map_file) + " --scan " + quote(scan) +
                                      " --prior 6.7,4.3,-1.8 --estimator " + estimator);
    ASSERT_EQ(r.status, 0) << estimator << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("estimator"), estimator);
    EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - truth.x,
                         j.at("pose").at("y").get<double>() - truth.y),
              0.02)
        << estimator << ": " << r.out;
    EXPECT_EQ(j.at("verdict"), "localized") << r.out;
  }
  expect_cli_error(run_cli(dir, "localize --map " + quote(map_file) + " --scan " + quote(scan) +
                                    " --global --estimator icp"),
                   "--prior");
  const CliRun sim = run_cli(dir, "simulate --map " + quote(map_file) + " --pose 6.5,4.5,-2");
  ASSERT_EQ(sim.status, 0) << sim.err;
  const std::string readings = dir.write("r.json", sim.out);
  expect_cli_error(run_cli(dir, "localize --map " + quote(map_file) + " --readings " +
                                    quote(readings) + " --prior 6.5,4.5,-2 --estimator icp"),
                   "laser scan");
}

TEST_F(Cli, APolygonMapFeedsTheCorrelationEngine) {
  const std::string map_file = test::maps_dir() + "/polygons/room_l.yaml";
  const CliRun sim = run_cli(dir, "simulate --map " + quote(map_file) + " --pose 1.5,1.5,0.3");
  ASSERT_EQ(sim.status, 0) << sim.err;
  const std::string readings = dir.write("r.json", sim.out);
  const CliRun r = run_cli(dir, "localize --map " + quote(map_file) + " --readings " +
                                    quote(readings) + " --prior 1.7,1.3,0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - 1.5,
                       j.at("pose").at("y").get<double>() - 1.5),
            0.1)
      << r.out;
  const std::string open = dir.write("open.yaml", "boundary: [[0, 0], [4, 0], [4, 3], [0, 3]]\n");
  expect_cli_error(run_cli(dir, "localize --map " + quote(open) + " --readings " + quote(readings) +
                                    " --prior 1,1,0"),
                   "not closed");
}

TEST_F(Cli, HallwayReportsSeed004sFigures) {
  const CliRun r = run_cli(dir, "hallway --seeds 5 --noise 0.02 --outliers scattered --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("seeds"), 5);
  EXPECT_EQ(j.at("successes"), 5);  // 100 of 100 over seeds 1-100 (engine/doc/icp.md)
  EXPECT_LT(j.at("mean_error_x_mm").get<double>(), 15.0);
  EXPECT_GT(j.at("mean_iterations").get<double>(), 1.0);
  expect_cli_error(run_cli(dir, "hallway --outliers rain"), "none, scattered or appearing");
  expect_cli_error(run_cli(dir, "hallway --seeds 0"), "seeds");
}

// simulate --firings writes consecutive firings; localize filters them (the echo filter)
// and says which sonars it rejected.
TEST_F(Cli, SeveralFiringsGoThroughTheEchoFilter) {
  const std::string room_l = test::map_path("room_l");
  const CliRun sim = run_cli(dir, "simulate --map " + quote(room_l) +
                                      " --pose 2.4,1.6,0.3 --sigma 0.02 --crosstalk 0.3 "
                                      "--firings 3 --seed 4");
  ASSERT_EQ(sim.status, 0) << sim.err;
  const auto written = nlohmann::json::parse(sim.out);
  ASSERT_EQ(written.at("firings_m").size(), 3u);
  EXPECT_EQ(written.at("ranges_m"), written.at("firings_m")[0]);
  const std::string readings = dir.write("f.json", sim.out);
  const CliRun r = run_cli(dir, "localize --map " + quote(room_l) + " --readings " +
                                    quote(readings) + " --prior 2.6,1.5,0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("echo_filter").at("firings").get<int>(), 3);
  EXPECT_FALSE(j.at("echo_filter").at("rejected_sonars").empty()) << r.out;  // 30 % crosstalk
  EXPECT_LE(std::hypot(j.at("pose").at("x").get<double>() - 2.4,
                       j.at("pose").at("y").get<double>() - 1.6),
            0.10)
      << r.out;
  expect_cli_error(run_cli(dir, "simulate --map " + quote(room_l) + " --pose 2,2,0 --firings 0"),
                   "--firings");
}

// Every command checks a number the same way (issue 31): "<flag> <rule>, got <value>", the
// value as the user wrote it (not std::to_string's six decimals).
TEST_F(Cli, ANumberOutOfRangeIsOneMessageForm) {
  const std::string room_l = quote(test::map_path("room_l"));
  const std::string simulate = "simulate --map " + room_l + " --pose 2,2,0 ";
  expect_cli_error(run_cli(dir, simulate + "--firings 0"),
                   {"--firings must lie in [1, 100], got 0"});
  expect_cli_error(run_cli(dir, simulate + "--scan --beams 0"),
                   {"--beams must lie in [1, 100000], got 0"});
  const std::string readings = dir.file("readings.json");
  ASSERT_EQ(run_cli(dir, simulate + "--out " + quote(readings)).status, 0);
  const std::string localize =
      "localize --map " + room_l + " --readings " + quote(readings) + " --global ";
  expect_cli_error(run_cli(dir, localize + "--repeat 0"), {"--repeat must be >= 1, got 0"});
  expect_cli_error(run_cli(dir, localize + "--second-peak-floor 1.5"),
                   {"--second-peak-floor must lie in [0, 1), got 1.5"});
  expect_cli_error(run_cli(dir, localize + "--budget-ms -0.5"),
                   {"--budget-ms must be a finite number >= 0, got -0.5"});
}

TEST_F(Cli, LocalizeGivesTheVerdict) {
  const std::string room_l = test::map_path("room_l");
  const CliRun sim = run_cli(dir, "simulate --map " + quote(room_l) + " --pose 2.4,1.6,0.3");
  ASSERT_EQ(sim.status, 0) << sim.err;
  const std::string readings = dir.write("r.json", sim.out);
  const CliRun r = run_cli(dir, "localize --map " + quote(room_l) + " --readings " +
                                    quote(readings) + " --prior 2.6,1.5,0.4");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("verdict").get<std::string>(), "localized");
  EXPECT_FALSE(j.at("ambiguous").get<bool>());
  const double confidence = j.at("confidence");
  const auto& parts = j.at("confidence_parts");
  const double product = parts.at("fit").get<double>() * parts.at("agreement").get<double>() *
                         parts.at("distinctness").get<double>() *
                         parts.at("sharpness").get<double>();
  EXPECT_NEAR(confidence, product, 1e-12);
  EXPECT_EQ(j.at("covariance").size(), 3u);
}

}  // namespace
}  // namespace gridloc
