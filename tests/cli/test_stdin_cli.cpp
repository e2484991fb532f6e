// End-to-end tests of `-` for standard input in the gridloc tool's input options (issue 18):
// a map, a ring and a CARMEN log (plain and gzip) read from standard input give what their
// files give; two `-` in one command, an empty standard input and one over --max-file-mb are
// one-line errors; and every run removes its copy of standard input.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "cli_support.hpp"
#include "flaser_log.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::expect_cli_error;
using test::quote;
using test::read_file;
using test::run_cli;
using test::TempDir;

/// The tool's temporary folder ($TMPDIR) is the test's own, so that each test can check that
/// no copy of standard input is left behind; the bundled maps are found by name.
class StdinCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("GRIDLOC_DATA_DIR", test::maps_dir().c_str(), 1);
    if (const char* before = std::getenv("TMPDIR")) tmpdir_before_ = before;
    fs::create_directories(tool_tmp_);
    ::setenv("TMPDIR", tool_tmp_.c_str(), 1);
  }
  void TearDown() override {
    if (tmpdir_before_) {
      ::setenv("TMPDIR", tmpdir_before_->c_str(), 1);
    } else {
      ::unsetenv("TMPDIR");
    }
    EXPECT_TRUE(fs::is_empty(tool_tmp_)) << "a copy of standard input was left in " << tool_tmp_;
  }

  /// Readings simulated on room_rect at 1,1,0, in a file.
  std::string readings() {
    const std::string path = dir.file("readings.json");
    const CliRun r =
        run_cli(dir, "simulate --map " + quote(map) + " --pose 1,1,0 --out " + quote(path));
    EXPECT_EQ(r.status, 0) << r.err;
    return path;
  }

  TempDir dir;
  std::string tool_tmp_ = dir.file("tool_tmp");
  std::optional<std::string> tmpdir_before_;
  std::string map = test::map_path("room_rect");
};

/// The current folder set to `folder` for the object's life.
class InFolder {
 public:
  explicit InFolder(const fs::path& folder) : before_(fs::current_path()) {
    fs::current_path(folder);
  }
  ~InFolder() { fs::current_path(before_); }
  InFolder(const InFolder&) = delete;
  InFolder& operator=(const InFolder&) = delete;

 private:
  fs::path before_;
};

/// The pose of localize's JSON answer.
nlohmann::json pose_of(const CliRun& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  return r.status == 0 ? nlohmann::json::parse(r.out).at("pose") : nlohmann::json();
}

// A map_server YAML from standard input finds its image in the current folder, and gives the
// file's answer; without the image there, the error names standard input and the image.
TEST_F(StdinCli, MapServerMapFromStandardInput) {
  const std::string r = readings();
  const std::string localize = "localize --readings " + quote(r) + " --prior 1.2,0.9,0.2 --map ";
  const nlohmann::json from_file = pose_of(run_cli(dir, localize + quote(map)));
  {
    InFolder maps(test::maps_dir());
    EXPECT_EQ(pose_of(run_cli(dir, localize + "- < " + quote(map))), from_file);
  }
  InFolder elsewhere(dir.path());
  expect_cli_error(run_cli(dir, localize + "- < " + quote(map)),
                   {"standard input", "room_rect.pgm", "not found"});
}

// A polygon map from standard input, told by its `boundary`: the same sectors, and the same
// readings simulated on it rasterized, as from its file.
TEST_F(StdinCli, PolygonMapFromStandardInput) {
  const std::string polygons = test::maps_dir() + "/polygons/room_rect.yaml";
  const auto sectors = [&](const std::string& input) {
    const CliRun r = run_cli(dir, "sectors --json --polygons " + input);
    EXPECT_EQ(r.status, 0) << r.err;
    nlohmann::json answer = r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
    answer.erase("polygons");  // the option's value: the file, or -
    return answer;
  };
  const nlohmann::json from_file = sectors(quote(polygons));
  ASSERT_TRUE(from_file.contains("sectors")) << from_file;
  EXPECT_EQ(sectors("- < " + quote(polygons)), from_file);
  const std::string simulate = "simulate --pose 1,1,0.3 --map ";
  const CliRun readings_from_file = run_cli(dir, simulate + quote(polygons));
  ASSERT_EQ(readings_from_file.status, 0) << readings_from_file.err;
  const CliRun piped = run_cli(dir, simulate + "- < " + quote(polygons));
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(piped.out, readings_from_file.out);
}

// `--ring -`: the same answer as the ring's file.
TEST_F(StdinCli, RingFromStandardInput) {
  const std::string localize =
      "localize --map " + quote(map) + " --readings " + quote(readings()) + " --prior 1.2,0.9,0.2";
  const nlohmann::json from_file =
      pose_of(run_cli(dir, localize + " --ring " + quote(test::ring_path())));
  EXPECT_EQ(pose_of(run_cli(dir, localize + " --ring - < " + quote(test::ring_path()))), from_file);
}

/// `text` gzip-compressed into `path`.
void write_gzip(const std::string& path, const std::string& text) {
  gzFile file = gzopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  ASSERT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  ASSERT_EQ(gzclose(file), Z_OK);
}

// A CARMEN log from standard input, plain or gzip (told by its bytes, as there is no name):
// the same map as from the file.
TEST_F(StdinCli, LogFromStandardInputPlainAndGzip) {
  const std::string log = dir.write("room.log", test::flaser_log(30, 2.0));
  const std::string gz = dir.file("room.log.gz");
  write_gzip(gz, read_file(log));
  const auto draw = [&](const std::string& input, const std::string& name) {
    const std::string out = dir.file(name + ".yaml");
    const CliRun r = run_cli(dir, "map-from-log --json --out " + quote(out) + " --log " + input);
    EXPECT_EQ(r.status, 0) << name << ": " << r.err;
    // The map's summary (its size and extent) and the drawn image.
    const nlohmann::json drawn = r.status == 0 ? nlohmann::json::parse(r.out).at("map") : nullptr;
    return std::pair{drawn, read_file(dir.file(name + ".pgm"))};
  };
  const auto from_file = draw(quote(log), "file");
  ASSERT_FALSE(from_file.second.empty());
  EXPECT_EQ(draw("- < " + quote(log), "plain"), from_file);
  EXPECT_EQ(draw("- < " + quote(gz), "gzip"), from_file);
}

// Standard input can be read once: two `-` in one command are refused, naming both.
TEST_F(StdinCli, TwoStandardInputsAreRefused) {
  const std::string ring = quote(test::ring_path());
  expect_cli_error(
      run_cli(dir, "localize --map - --ring - --readings x.json --prior 1,1,0 < " + ring),
      {"--map and --ring", "standard input", "only once"});
  expect_cli_error(run_cli(dir, "simulate --map - --ring - --pose 1,1,0 < " + ring),
                   {"--map and --ring", "standard input"});
  expect_cli_error(run_cli(dir, "eval --maps -,- < " + quote(map)),
                   {"--maps reads standard input (-) twice"});
  expect_cli_error(run_cli(dir, "merge - - < " + ring), {"files reads standard input (-) twice"});
}

// An empty standard input is an error naming the option, not an empty file's error.
TEST_F(StdinCli, EmptyStandardInputIsRefused) {
  expect_cli_error(run_cli(dir, "simulate --map - --pose 1,1,0 < /dev/null"),
                   {"--map", "standard input is empty"});
  expect_cli_error(
      run_cli(dir, "map-from-log --log - --out " + quote(dir.file("m.yaml")) + " < /dev/null"),
      {"--log", "standard input is empty"});
}

// Standard input is held to --max-file-mb as files are (in whole MB): a longer one is refused
// while it is read, naming standard input and the limit.
TEST_F(StdinCli, StandardInputOverTheFileLimitIsRefused) {
  const std::string r = readings();
  const std::string big =
      dir.write("big.json", read_file(r) + std::string(1024 * 1024 + 1000, ' '));
  const std::string localize =
      "--max-file-mb 1 localize --map " + quote(map) + " --prior 1.2,0.9,0.2 --readings ";
  const CliRun within = run_cli(dir, localize + "- < " + quote(r));
  EXPECT_EQ(within.status, 0) << within.err;
  expect_cli_error(
      run_cli(dir, localize + "- < " + quote(big)),
      {"--readings", "standard input", "larger than the limit of 1 MB", "--max-file-mb"});
  expect_cli_error(run_cli(dir, localize + quote(big)), {"big.json", "--max-file-mb"});
}

}  // namespace
}  // namespace gridloc
