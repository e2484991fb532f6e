#pragma once
/// `-` for standard input wherever the CLI reads a file (issue 18). The library never reads
/// standard input: the CLI copies it, once per run and at most --max-file-mb of it, into a
/// private temporary folder, hands the copy's path to the loaders, and main names the copy
/// "standard input" in every error. At most one option of a command may be `-`.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace gridloc::cli {

/// The value that stands for standard input.
inline constexpr const char* kStdin = "-";

/// An option that reads a file: `-` in it means standard input. A `list` option holds
/// comma-separated files (`--maps a,-`), one of which may be `-`.
struct InputOption {
  std::string name;
  bool list = false;
};

/// Refuses, once `cmd` is parsed, a command line that gives `-` to more than one of `inputs`
/// (or twice to one): a gridloc::Error naming both, as standard input can be read only once.
void read_stdin_at_most_once(CLI::App* cmd, std::vector<InputOption> inputs);

/// The file to read for an input option's value: `path` itself, or for `-` the copy of
/// standard input (made on the first call). Throws gridloc::Error naming `option` when
/// standard input is empty or longer than --max-file-mb.
std::string input_path(const std::string& path, const std::string& option);

/// The copy of standard input under a name ending in `extension` (".bt"), for loaders that
/// tell a file's kind by its extension; input_path(kStdin, option) must have made it.
std::string stdin_path_with_extension(const std::string& extension);

/// The first line of the copy of standard input (at most `max_bytes` of it).
std::string stdin_first_line(std::size_t max_bytes = 256);

/// `message` with the paths of the copy of standard input replaced by "standard input".
std::string name_standard_input(std::string message);

}  // namespace gridloc::cli
