// End-to-end tests of `gridloc eval PROTOCOL`: each protocol's own command gives the old
// spelling's JSON, the old spelling prints the new one, and each command takes only its
// options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace gridloc {
namespace {

using namespace test;
using Cli = CliTest;

/// `j` without its timings (keys ending in _ms): what two runs of one protocol share.
nlohmann::json without_timings(nlohmann::json j) {
  if (j.is_array()) {
    for (auto& item : j) item = without_timings(item);
  } else if (j.is_object()) {
    nlohmann::json kept = nlohmann::json::object();
    for (auto& [key, value] : j.items()) {
      const bool timing = key.size() >= 3 && key.compare(key.size() - 3, 3, "_ms") == 0;
      if (!timing) kept[key] = without_timings(value);
    }
    return kept;
  }
  return j;
}

/// The JSON of `gridloc eval ARGS --json --quiet`, without its timings.
nlohmann::json eval_json(const TempDir& dir, const std::string& args) {
  const CliRun r = run_cli(dir, "eval " + args + " --json --quiet");
  EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  EXPECT_EQ(r.err, "") << args;
  return r.status == 0 ? without_timings(nlohmann::json::parse(r.out)) : nlohmann::json();
}

TEST_F(Cli, EachProtocolsCommandGivesTheOldSpellingsResults) {
  const std::pair<const char*, const char*> spellings[] = {
      {"--trials 2 --maps room_rect --echo-filter",
       "sonar --trials 2 --maps room_rect --echo-filter"},
      {"--laser --trials 2 --maps room_l --estimators correlation,icp",
       "laser --trials 2 --maps room_l --estimators correlation,icp"},
      {"--drive 1.5 --drive-firings 3 --drive-windowed --trials 2 --maps room_l",
       "drive --distance 1.5 --firings 3 --windowed --trials 2 --maps room_l"},
      {"--estimator sectors --trials 2", "sectors --estimators sectors --trials 2"},
      {"--protocol disambiguation --environments 1 --starts 1 --repeats 1 --points 5",
       "disambiguation --environments 1 --starts 1 --repeats 1 --points 5"},
      {"--protocol team --trials 2 --robots 1,2", "team --trials 2 --robots 1,2"},
  };
  for (const auto& [old_spelling, command] : spellings) {
    const nlohmann::json old_json = eval_json(dir, old_spelling);
    ASSERT_FALSE(old_json.is_null()) << old_spelling;
    EXPECT_EQ(old_json, eval_json(dir, command)) << command;
  }
}

TEST_F(Cli, TheOldSpellingPrintsTheNewOne) {
  const CliRun r =
      run_cli(dir, "eval --drive 1.5 --drive-windowed --trials 1 --maps room_l --json --points 5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto err = lines(r.err);
  ASSERT_FALSE(err.empty());
  // --points belongs to the disambiguation protocol: it had no effect, and is left out.
  EXPECT_EQ(err.back(),
            "gridloc eval: this spelling keeps working; its protocol's own command is: gridloc "
            "eval drive --maps room_l --trials 1 --json --distance 1.5 --windowed");
}

TEST_F(Cli, EvalHelpListsTheProtocolsEachWithOnlyItsOptions) {
  const CliRun help = run_cli(dir, "eval --help");
  ASSERT_EQ(help.status, 0) << help.err;
  for (const char* protocol : {"sonar", "laser", "drive", "sectors", "disambiguation", "team"}) {
    EXPECT_NE(help.out.find("\n  " + std::string(protocol) + " "), std::string::npos) << protocol;
  }
  EXPECT_EQ(help.out.find("\n  --drive"), std::string::npos) << help.out;  // the old spelling's
  const CliRun team = run_cli(dir, "eval team --help");
  EXPECT_NE(team.out.find("--robots"), std::string::npos) << team.out;
  EXPECT_EQ(team.out.find("--noisy"), std::string::npos) << team.out;
  expect_cli_error(run_cli(dir, "eval sonar --drive 2 --trials 1"), "--drive");
  expect_cli_error(run_cli(dir, "eval drive --laser-beams 90 --trials 1"), "--laser-beams");
  expect_cli_error(run_cli(dir, "eval --maps room_l drive --trials 1"),
                   {"eval drive", "--maps", "before"});
  expect_cli_error(run_cli(dir, "eval sonar --maps polygons/room_l --trials 1"),
                   {"polygon", "eval sectors"});
  expect_cli_error(run_cli(dir, "eval sectors --maps room_l --trials 1"), "polygon maps");
  expect_cli_error(run_cli(dir, "eval drive --distance 30 --trials 1"), {"--distance", "(0, 20]"});
  expect_cli_error(run_cli(dir, "eval disambiguation --sensor ir"), "--sensor");
}

// --calibration-plot draws each configuration's coverage curve (issue 19) into a PNG.
TEST_F(Cli, TheCalibrationPlotIsAPng) {
  const std::string png = dir.file("calibration.png");
  const CliRun r = run_cli(dir,
                           "eval sonar --trials 3 --maps room_rect --quiet --json "
                           "--calibration-plot " +
                               quote(png));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_file(png).substr(1, 3), "PNG");
  expect_cli_error(run_cli(dir,
                           "eval laser --trials 1 --maps room_rect --quiet "
                           "--calibration-plot " +
                               quote(dir.file("none/c.png"))),
                   "c.png");
}

}  // namespace
}  // namespace gridloc
