#pragma once
// Old spellings of options and commands (issue 31): they keep working and name themselves in
// errors, but stay out of --help, which shows the new ones.
#include <CLI/CLI.hpp>

namespace gridloc::cli {

/// The heading an old spelling's options are registered under.
inline constexpr const char* kOldSpelling = "Old spelling";

/// Leaves the kOldSpelling options out of `cmd`'s --help (CLI11 would drop a group named ""
/// from the help too, but then also the option's name from its error messages).
void hide_old_spellings(CLI::App* cmd);

}  // namespace gridloc::cli
