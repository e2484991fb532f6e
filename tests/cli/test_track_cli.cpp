// End-to-end tests of `gridloc track` (issue 13): the Localizer through a CARMEN log of front
// scans simulated in a corridor, its JSON Lines contract, odometry from the laser lines or
// from ODOM lines, and bad input as one error line with exit status 2.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "../localizer/laser_cases.hpp"
#include "cli_support.hpp"
#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_cli_error;
using test::lines;
using test::quote;
using test::run_cli;
using test::TempDir;

/// A drive along the corridor from x = 8.5 to 11.5, 0.25 m a scan, one scan a second.
std::vector<Pose2> corridor_drive() {
  std::vector<Pose2> poses;
  for (int k = 0; k <= 12; ++k) poses.push_back({8.5 + 0.25 * k, 2.5 + 0.02 * (k % 3), 0.01 * k});
  return poses;
}

/// A CARMEN log of 181-beam front scans (3 m) at `poses`; with ODOM lines when `odom`.
std::string corridor_log(const TempDir& dir, const std::vector<Pose2>& poses, bool odom) {
  const OccupancyMap map = test::door_corridor();
  std::ostringstream log;
  char buf[96];
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const Pose2& p = poses[k];
    const RangeScan scan = test::front_scan(map, p, 3.0);
    std::snprintf(buf, sizeof buf, " %.6f %.6f %.6f", p.x, p.y, p.theta);
    if (odom) log << "ODOM" << buf << " 0 0 0 " << k << ".0 test " << k << ".0\n";
    log << "FLASER " << scan.ranges.size();
    for (double r : scan.ranges) log << " " << (r >= 3.0 ? 81.91 : r);
    log << buf << buf << " " << k << ".0 test " << k << ".0\n";
  }
  return dir.write(odom ? "corridor_odom.log" : "corridor.log", log.str());
}

class TrackCli : public ::testing::Test {
 protected:
  void SetUp() override {
    map = dir.file("corridor.yaml");
    save_ros_map(test::door_corridor(), map);
    log = corridor_log(dir, corridor_drive(), false);
  }
  std::vector<nlohmann::json> track(const std::string& extra) {
    const test::CliRun run = run_cli(dir, "track --map " + quote(map) + " --log " + quote(log) +
                                              " --max-range 3 --json --truth-from-log " + extra);
    EXPECT_EQ(run.status, 0) << run.err;
    std::vector<nlohmann::json> steps;
    for (const std::string& line : lines(run.out)) steps.push_back(nlohmann::json::parse(line));
    return steps;
  }
  TempDir dir;
  std::string map, log;
};

TEST_F(TrackCli, FromAPriorEveryScanIsTrackedWithTheContractsFields) {
  const std::vector<nlohmann::json> steps = track("--prior 8.55,2.45,0.02");
  ASSERT_EQ(steps.size(), corridor_drive().size());
  for (const nlohmann::json& step : steps) {
    for (const char* field :
         {"index", "time", "pose", "verdict", "confidence", "hypotheses", "alternatives",
          "covariance", "travelled_m", "timing_ms", "error_m", "error_deg"}) {
      EXPECT_TRUE(step.contains(field)) << field;
    }
    EXPECT_LE(step["error_m"].get<double>(), 0.10) << step.dump();  // issue 13: laser success
    EXPECT_LE(step["error_deg"].get<double>(), 2.0) << step.dump();
  }
  EXPECT_NEAR(steps.back()["travelled_m"].get<double>(), 3.0, 0.05);
  EXPECT_EQ(steps.back()["index"].get<int>(), 12);
}

// The default grid is the laser tracking field (with_laser_tracking_grid); the contour-thinned
// grid of seed 001 tracks the same drive.
TEST_F(TrackCli, OnTheThinnedGridEveryScanIsTrackedToo) {
  const std::vector<nlohmann::json> steps = track("--prior 8.55,2.45,0.02 --global-grid thinned");
  ASSERT_EQ(steps.size(), corridor_drive().size());
  for (const nlohmann::json& step : steps) {
    EXPECT_LE(step["error_m"].get<double>(), 0.10) << step.dump();
    EXPECT_LE(step["error_deg"].get<double>(), 2.0) << step.dump();
  }
}

// --reported-floor-m and -deg (issue 19): the map's own error, added to what is reported after
// every decision, so the poses and verdicts are those of the default floor.
TEST_F(TrackCli, TheReportedFloorWidensTheCovarianceOnly) {
  const std::vector<nlohmann::json> base = track("--prior 8.55,2.45,0.02");
  const std::vector<nlohmann::json> rough =
      track("--prior 8.55,2.45,0.02 --reported-floor-m 0.1 --reported-floor-deg 3");
  ASSERT_EQ(rough.size(), base.size());
  const double floor_m = LocalizerOptions{}.reported_floor_m;
  const double floor_rad = LocalizerOptions{}.reported_floor_rad;
  for (std::size_t k = 0; k < base.size(); ++k) {
    EXPECT_EQ(rough[k]["pose"], base[k]["pose"]) << k;
    EXPECT_EQ(rough[k]["verdict"], base[k]["verdict"]) << k;
    const nlohmann::json &wide = rough[k]["covariance"], &narrow = base[k]["covariance"];
    for (int axis = 0; axis < 2; ++axis) {
      EXPECT_NEAR(wide[axis][axis].get<double>() - narrow[axis][axis].get<double>(),
                  0.1 * 0.1 - floor_m * floor_m, 1e-12)
          << k;
    }
    EXPECT_NEAR(wide[2][2].get<double>() - narrow[2][2].get<double>(),
                std::pow(3.0 * std::numbers::pi / 180.0, 2) - floor_rad * floor_rad, 1e-12)
        << k;
  }
}

TEST_F(TrackCli, GloballyTheDriveFavoursTheTruthWithoutAWrongAnswer) {
  // A 3 m front laser in a corridor of look-alikes: the drive's scans fused into one view;
  // the same with every place searched in full (--light-place-weight 0) and with every place
  // of an ambiguous set searched in its window alone (1).
  for (const char* light : {"", " --light-place-weight 0", " --light-place-weight 1"}) {
    const std::vector<nlohmann::json> steps =
        track(std::string("--global --every 2 --odometry-noise 0.02,1 --fuse-drive") + light);
    ASSERT_EQ(steps.size(), 7u) << light;  // scans 0, 2, ..., 12
    for (const nlohmann::json& step : steps) {
      if (step["verdict"] == "localized") {
        EXPECT_LE(step["error_m"].get<double>(), 0.05) << light;
      }
    }
    // 3 m of driving: the truth is the heaviest place, its weight in the JSON.
    const nlohmann::json& last = steps.back();
    EXPECT_LE(last["error_m"].get<double>(), 0.05) << light << last.dump();
    EXPECT_GT(last["alternatives"][0]["weight"].get<double>(), 0.5) << light << last.dump();
  }
}

// From no prior in a corridor of look-alikes the answer is `ambiguous`, then the first place
// waits for the drive to bear it out: every answer held back names its rule in the JSON
// (`held_back`), and the summary counts them by rule.
TEST_F(TrackCli, AnswersHeldBackNameTheRuleAndTheSummaryCountsThem) {
  const std::vector<nlohmann::json> steps = track("--global");
  std::map<std::string, int> held_back;
  for (const nlohmann::json& step : steps) {
    EXPECT_EQ(step["verdict"] == "not localized", step["held_back"] != "none") << step.dump();
    if (step["verdict"] == "not localized") ++held_back[step["held_back"].get<std::string>()];
  }
  ASSERT_GT(held_back["confirming"], 0);
  const test::CliRun run = run_cli(
      dir, "track --map " + quote(map) + " --log " + quote(log) + " --max-range 3 --global");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("not localized, held back by:"), std::string::npos) << run.out;
  for (const auto& [reason, count] : held_back) {
    EXPECT_NE(run.out.find(" " + reason + " " + std::to_string(count)), std::string::npos)
        << reason << " " << count << ": " << run.out;
  }
}

TEST_F(TrackCli, OdometryFromOdomLines) {
  log = corridor_log(dir, corridor_drive(), true);
  const std::vector<nlohmann::json> steps = track("--prior 8.5,2.5,0 --odometry odom");
  ASSERT_EQ(steps.size(), corridor_drive().size());
  EXPECT_LE(steps.back()["error_m"].get<double>(), 0.05);
}

TEST_F(TrackCli, TheHeldOutPartIsTheOddBlocksFromAPriorTakenFromTheLog) {
  // Timestamps 0..12 s in blocks of 4 s: scans 4-7 and 12 are held out.
  const std::vector<nlohmann::json> steps = track("--prior-from-log --part held-out --block-s 4");
  ASSERT_EQ(steps.size(), 5u);
  EXPECT_EQ(steps.front()["index"].get<int>(), 4);
  EXPECT_EQ(steps.back()["index"].get<int>(), 12);
  for (const nlohmann::json& step : steps) EXPECT_LE(step["error_m"].get<double>(), 0.10);
}

TEST_F(TrackCli, APriorFromTheLogPlacesAScanOneScanCannotPlace) {
  // Scan 8 stands at (10.5, 2.5) facing the north door: alone, it is ambiguous.
  const std::vector<nlohmann::json> global = track("--global --start 8 --count 1");
  ASSERT_EQ(global.size(), 1u);
  EXPECT_EQ(global[0]["verdict"], "ambiguous");
  const std::vector<nlohmann::json> tracked = track("--prior-from-log --start 8 --count 1");
  ASSERT_EQ(tracked.size(), 1u);
  EXPECT_EQ(tracked[0]["verdict"], "localized");
  EXPECT_LE(tracked[0]["error_m"].get<double>(), 0.10);
}

TEST_F(TrackCli, GlobalTrialsReportEachTrialAndASummary) {
  const std::vector<nlohmann::json> lines = track("--global --trials 3 --drive-m 1");
  ASSERT_EQ(lines.size(), 4u);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(lines[t]["trial"].get<int>(), t);
    // Each drive goes on for 1 m, or to the log's last scan.
    const nlohmann::json& end = lines[t]["end"];
    EXPECT_TRUE(end["travelled_m"].get<double>() >= 1.0 - 1e-9 || end["index"].get<int>() == 12)
        << end.dump();
    EXPECT_TRUE(lines[t]["standstill"].contains("right"));
  }
  const nlohmann::json& summary = lines.back()["summary"];
  EXPECT_EQ(summary["trials"].get<int>(), 3);
  EXPECT_GE(summary["drive_success_pct"].get<double>(), 0.0);
}

/// `json` without its "timing_ms" fields (the only ones that differ between two runs).
nlohmann::json without_timings(nlohmann::json json) {
  if (!json.is_object()) return json;
  json.erase("timing_ms");
  for (auto& [key, value] : json.items()) value = without_timings(value);
  return json;
}

TEST_F(TrackCli, TwoShardsMergedAreOneRun) {
  const std::string trials = "--global --trials 5 --drive-m 1 ";
  const std::vector<nlohmann::json> whole = track(trials);
  std::vector<std::string> files;
  for (const char* shard : {"2/2", "1/2"}) {
    const test::CliRun run =
        run_cli(dir, "track --map " + quote(map) + " --log " + quote(log) +
                         " --max-range 3 --json --truth-from-log " + trials + "--shard " + shard);
    ASSERT_EQ(run.status, 0) << run.err;
    files.push_back(dir.write(std::string("shard") + shard[0] + ".jsonl", run.out));
  }
  const nlohmann::json last = nlohmann::json::parse(lines(test::read_file(files[0])).back());
  EXPECT_EQ(last["shard"]["index"].get<int>(), 2);
  EXPECT_EQ(last["summary"]["trials"].get<int>(), 2);  // trials 1 and 3
  const test::CliRun merged = run_cli(dir, "merge " + quote(files[0]) + " " + quote(files[1]));
  ASSERT_EQ(merged.status, 0) << merged.err;
  const std::vector<std::string> merged_lines = lines(merged.out);
  ASSERT_EQ(merged_lines.size(), whole.size());
  for (std::size_t k = 0; k < whole.size(); ++k) {
    EXPECT_EQ(without_timings(nlohmann::json::parse(merged_lines[k])), without_timings(whole[k]))
        << "line " << k;
  }
  // Bad shards: a missing one, one given twice, shards of another run, a whole run, a line
  // that is not JSON, a shard that did not finish.
  expect_cli_error(run_cli(dir, "merge " + quote(files[0])), {"shard 1/2", "missing"});
  expect_cli_error(run_cli(dir, "merge " + quote(files[0]) + " " + quote(files[0])),
                   {"shard 2", "also"});
  const test::CliRun other = run_cli(dir, "track --map " + quote(map) + " --log " + quote(log) +
                                              " --max-range 3 --json --global --trials 4 "
                                              "--drive-m 1 --shard 1/2");
  const std::string other_file = dir.write("other.jsonl", other.out);
  expect_cli_error(run_cli(dir, "merge " + quote(files[0]) + " " + quote(other_file)),
                   {"not one run"});
  std::string whole_text;
  for (const nlohmann::json& line : whole) whole_text += line.dump() + "\n";
  expect_cli_error(run_cli(dir, "merge " + quote(dir.write("whole.jsonl", whole_text))),
                   {"not a shard", "--shard"});
  expect_cli_error(run_cli(dir, "merge " + quote(dir.write("bad.jsonl", "{\"trial\": 1}\nnope\n"))),
                   {"bad.jsonl:1", "trial"});
  const std::string cut = test::read_file(files[1]);
  expect_cli_error(
      run_cli(dir, "merge " + quote(files[0]) + " " +
                       quote(dir.write("cut.jsonl", cut.substr(0, cut.find("\n") + 1)))),
      {"cut.jsonl", "did not finish"});
  expect_cli_error(run_cli(dir, "merge " + quote(dir.file("none.jsonl"))), {"none.jsonl"});
}

/// Tracks `building`'s held-out half (its map part drawn first) with `extra` options: no
/// `localized` answer is more than 0.3 m or 5 degrees off, and at least `min_localized` are
/// `localized`. Skips when ../shared is absent.
void expect_never_wrong(const std::string& building, const std::string& extra, int min_localized) {
  const std::string log = std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/acschaefer_ple/" +
                          building + "-corrected.log.gz";
  if (!std::filesystem::exists(log)) {
    GTEST_SKIP() << "../shared is absent (" << log << "): real-log test skipped";
  }
  TempDir dir;
  const std::string map = dir.file(building + ".yaml");
  const test::CliRun drawn =
      run_cli(dir, "map-from-log --log " + quote(log) + " --out " + quote(map) + " --part map");
  ASSERT_EQ(drawn.status, 0) << drawn.err;
  const test::CliRun run = run_cli(dir, "track --map " + quote(map) + " --log " + quote(log) +
                                            " --part held-out --truth-from-log --json " + extra);
  ASSERT_EQ(run.status, 0) << run.err;
  int localized = 0;
  for (const std::string& line : lines(run.out)) {
    const nlohmann::json step = nlohmann::json::parse(line);
    if (step["verdict"] != "localized") continue;
    ++localized;
    EXPECT_LE(step["error_deg"].get<double>(), 5.0) << step["index"];
    EXPECT_LE(step["error_m"].get<double>(), 0.3) << step["index"];
  }
  EXPECT_GE(localized, min_localized);
}

// The Intel lab through a turn on the spot (scans 810-849), the log's own corrected poses as
// odometry: a window whose heading spread is wider than a localized place's (scan 835,
// matched 7 degrees off) is not `localized`.
TEST(TrackRealLog, AWindowSpreadWiderThanLocalizedIsNotLocalized) {
  expect_never_wrong("intel", "--prior-from-log --start 810 --count 40", 10);
}

// csail through a turn (scans 40-69) on 2 % + 1 deg/m odometry: scan 55 fits at 62 % of the
// place's usual score 5-7 degrees from the odometry's heading (turn_fit_ratio).
TEST(TrackRealLog, AWeakFitThatTurnsThePlaceIsNotLocalized) {
  expect_never_wrong("csail",
                     "--prior-from-log --start 40 --count 30 --odometry-noise 0.02,1 --seed 1", 6);
}

// belgioioso from no prior at held-out scan 373, driving 6 m on 2 % + 1 deg/m: the first scan
// fits the corridor turned round 15 m away 3 % better than anything near the truth; with
// only its best places kept the track followed it, `localized` 13 m off after a metre
// (first_drop_ratio keeps the look-alikes, and the drive does not pick one wrongly).
TEST(TrackRealLog, TheFirstScansLookAlikesAreKept) {
  expect_never_wrong("belgioioso", "--global --start 373 --count 12 --odometry-noise 0.02,1", 0);
}

// orebro's held-out scans 210-219 on 2 % + 1 deg/m odometry: scans 213-219 see a place the
// map's half barely saw (fits of 20-35 % of the usual). A missed window's look-alike that
// missed too merged into the track and turned it 10-13 degrees, then lost it (3 of 10
// `localized`); kept on the odometry, the weak fit right after the plain miss at 213 is
// 0.37 m off and must not be `localized` (5 of 10, none wrong).
TEST(TrackRealLog, AMissedWindowsLookAlikesDoNotTurnTheTrack) {
  expect_never_wrong("orebro",
                     "--prior-from-log --start 205 --count 20 --odometry-noise 0.02,1 --seed 1", 5);
}

TEST_F(TrackCli, BadInputIsOneErrorLine) {
  const std::string base = "track --map " + quote(map) + " --log " + quote(log) + " ";
  expect_cli_error(run_cli(dir, base + "--prior 1,2,0 --global"), {"--prior", "--global"});
  expect_cli_error(run_cli(dir, base), {"--prior", "--global"});
  expect_cli_error(run_cli(dir, base + "--global --odometry wheels"), {"odometry", "wheels"});
  expect_cli_error(run_cli(dir, base + "--global --odometry odom"), {"ODOM"});
  expect_cli_error(run_cli(dir, base + "--global --every 0"), {"--every"});
  expect_cli_error(run_cli(dir, base + "--global --max-window-turn -5"),
                   {"--max-window-turn", "-5"});
  expect_cli_error(run_cli(dir, base + "--global --weak-fit-ratio 2"), {"--weak-fit-ratio", "2"});
  expect_cli_error(run_cli(dir, base + "--global --cells-per-update nan"),
                   {"--cells-per-update", "nan"});
  expect_cli_error(run_cli(dir, base + "--global --catch-up-steps -1"), {"--catch-up-steps", "-1"});
  expect_cli_error(run_cli(dir, base + "--global --global-grid fog"), {"--global-grid", "fog"});
  expect_cli_error(run_cli(dir, base + "--global --global-grid field --field-sigma -1"),
                   {"--field-sigma"});
  expect_cli_error(run_cli(dir, base + "--global --start 99"), {"--start", "13 scans"});
  expect_cli_error(run_cli(dir, base + "--global --odometry-noise 0.02"), {"--odometry-noise"});
  expect_cli_error(run_cli(dir, base + "--prior 1,x,0"), {"--prior"});
  expect_cli_error(run_cli(dir, base + "--prior-from-log --trials 2"), {"--trials", "--global"});
  expect_cli_error(run_cli(dir, base + "--global --trials 2 --shard 3/2"), {"--shard", "3/2"});
  expect_cli_error(run_cli(dir, base + "--global --trials 2 --shard two"), {"--shard", "K/N"});
  expect_cli_error(run_cli(dir, base + "--global --shard 1/2"), {"--shard", "--trials"});
  expect_cli_error(run_cli(dir, base + "--global --part odd"), {"--part", "odd"});
  expect_cli_error(run_cli(dir, "track --map " + quote(map) + " --global --log " +
                                    quote(dir.file("missing.log"))),
                   {"missing.log"});
  expect_cli_error(run_cli(dir, base + "--global --plot " + quote(dir.file("no/such/t.png"))),
                   {"--plot", "does not exist"});
  expect_cli_error(run_cli(dir, base + "--global --raw-odometry " + quote(dir.file("x.gfs"))),
                   {"x.gfs"});
  expect_cli_error(run_cli(dir, base + "--global --odometry-error 0.05"), {"--odometry-error"});
  expect_cli_error(run_cli(dir, base + "--global --entry-weight 0"), {"entry_weight"});
  expect_cli_error(run_cli(dir, base + "--global --reported-floor-m -1"),
                   {"--reported-floor-m", "-1"});
  expect_cli_error(run_cli(dir, base + "--global --reported-floor-deg nan"),
                   {"--reported-floor-deg", "nan"});
  expect_cli_error(run_cli(dir, base + "--global --light-place-weight 2"),
                   {"light_place_weight", "2"});
}

TEST_F(TrackCli, APlotShowsTheTrackAndTheWeights) {
  const std::string png = dir.file("track.png");
  const test::CliRun run = run_cli(dir, "track --map " + quote(map) + " --log " + quote(log) +
                                            " --max-range 3 --truth-from-log --prior 8.55,2.45,0.02"
                                            " --plot " +
                                            quote(png));
  ASSERT_EQ(run.status, 0) << run.err;
  const cv::Mat img = cv::imread(png);
  ASSERT_FALSE(img.empty());
  EXPECT_GT(img.cols, 700);
  EXPECT_GT(img.rows, 400);
  EXPECT_NE(run.out.find("update: median"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace gridloc
