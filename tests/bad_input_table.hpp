#pragma once
// The bad-input table of issue 14: the gridloc tool run end to end on inputs a user or an
// attacker could give it, under a memory limit (ulimit -v) and a time limit. Each case must
// exit 2 with exactly one `gridloc: error:` line containing the case's parts, nothing on
// stdout, and no signal. Cases live in tests/cli/test_bad_inputs_*.cpp, one table per area.
#include <gtest/gtest.h>

#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"

namespace gridloc::test {

/// One bad input: files written into a fresh folder, then the tool's arguments.
struct BadInputCase {
  std::string name;  ///< the test's name (letters, digits, underscores)
  /// Files to write before the run: (name inside the folder, content).
  std::vector<std::pair<std::string, std::string>> files;
  /// Arguments after `gridloc`; every "{dir}" is replaced by the folder's path and every
  /// "{maps}" by the bundled maps folder.
  std::string args;
  std::vector<std::string> parts;  ///< what the error line must contain
  /// Writes files that need code (large or binary ones) into the folder, after `files`.
  std::function<void(const TempDir&)> setup = {};
};

// AddressSanitizer reserves terabytes of shadow address space at start-up, so under it the
// runs go without the address-space limit (the Release suite keeps it).
#if defined(__SANITIZE_ADDRESS__)
#define GRIDLOC_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GRIDLOC_TEST_UNDER_ASAN 1
#endif
#endif

/// Address-space limit of every run (KiB): 3 GB, below a 4 GB robot computer's memory.
constexpr long kBadInputMemoryKiB = 3L * 1024 * 1024;

/// The shell's `ulimit -v` of every run ("" under AddressSanitizer).
inline std::string memory_limit_command() {
#ifdef GRIDLOC_TEST_UNDER_ASAN
  return "";
#else
  return "ulimit -v " + std::to_string(kBadInputMemoryKiB) + " && ";
#endif
}
/// Wall-clock limit of every run (s); a run that takes longer is killed and fails the case.
constexpr int kBadInputSeconds = 120;

inline std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

/// Runs one case and checks the error contract.
inline void run_bad_input(const BadInputCase& c) {
  TempDir dir;
  for (const auto& [name, content] : c.files) dir.write(name, content);
  if (c.setup) c.setup(dir);
  std::string args = replace_all(c.args, "{dir}", dir.path().string());
  args = replace_all(args, "{maps}", maps_dir());
  // `exec timeout` keeps the shell out of the way: a signal in gridloc shows as 128 + N.
  const std::string limited = "-c " + quote(memory_limit_command() + "exec timeout -s KILL " +
                                            std::to_string(kBadInputSeconds) + " \"$0\" \"$@\"");
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd = "sh " + limited + " " + quote(GRIDLOC_CLI_PATH) + " " + args + " >" +
                          quote(out) + " 2>" + quote(err);
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  SCOPED_TRACE("gridloc " + args);
  EXPECT_NE(r.status, 137) << "killed: over " << kBadInputSeconds << " s";
  expect_cli_error(r, {});
  const auto error_lines = lines(r.err);
  for (const auto& part : c.parts) {
    if (error_lines.size() != 1) break;
    EXPECT_NE(error_lines[0].find(part), std::string::npos)
        << "'" << error_lines[0] << "' lacks '" << part << "'";
  }
}

/// What gtest prints of a failing case: its arguments.
inline void PrintTo(const BadInputCase& c, std::ostream* os) {
  *os << "gridloc " << c.args;
}

/// gtest's parameter name of a case.
struct BadInputName {
  std::string operator()(const ::testing::TestParamInfo<BadInputCase>& info) const {
    return info.param.name;
  }
};

}  // namespace gridloc::test
