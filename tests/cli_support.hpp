#pragma once
// Helpers of the end-to-end tests of the gridloc tool: run it with arguments, capture its
// streams, check the one-line error contract. GRIDLOC_CLI_PATH is set by tests/CMakeLists.txt.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "gridloc/sensors/range_scan.hpp"
#include "test_support.hpp"

namespace gridloc::test {

struct CliRun {
  int status = -1;  ///< exit status, or -1 if the process did not exit normally
  std::string out;
  std::string err;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// `s` single-quoted for the shell.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs the gridloc binary with `args` (already quoted where needed), capturing both streams
/// into files of `dir`.
inline CliRun run_cli(const TempDir& dir, const std::string& args) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd =
      quote(GRIDLOC_CLI_PATH) + " " + args + " >" + quote(out) + " 2>" + quote(err);
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  std::string line;
  while (std::getline(ss, line)) v.push_back(line);
  return v;
}

/// Expects exit status 2, nothing on stdout, and exactly one stderr line starting with
/// "gridloc: error:" and containing every one of `parts`.
inline void expect_cli_error(const CliRun& r, std::initializer_list<std::string> parts) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "");
  const auto l = lines(r.err);
  ASSERT_EQ(l.size(), 1u) << "stderr: " << r.err;
  EXPECT_EQ(l[0].rfind("gridloc: error:", 0), 0u) << l[0];
  for (const auto& part : parts) {
    EXPECT_NE(l[0].find(part), std::string::npos) << "'" << l[0] << "' lacks '" << part << "'";
  }
}

inline void expect_cli_error(const CliRun& r, const std::string& part) {
  expect_cli_error(r, {part});
}

/// A scan as the `angle_rad,range_m` lines `localize --scan` reads, written to `dir`/`name`.
inline std::string write_scan_csv(TempDir& dir, const std::string& name, const RangeScan& s) {
  std::string csv;
  for (std::size_t k = 0; k < s.ranges.size(); ++k) {
    csv += std::to_string(s.angles[k]) + "," + std::to_string(s.ranges[k]) + "\n";
  }
  return dir.write(name, csv);
}

/// The fixture of the tool's end-to-end tests: a temporary folder, the bundled room_rect map
/// and wheelchair ring, and GRIDLOC_DATA_DIR set so that the tool finds bundled maps by name.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override { ::setenv("GRIDLOC_DATA_DIR", maps_dir().c_str(), 1); }
  TempDir dir;
  std::string map = map_path("room_rect");
  std::string ring = ring_path();
};

}  // namespace gridloc::test
