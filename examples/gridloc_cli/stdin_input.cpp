// Standard input as a file for the loaders: `-` in any input option of a command.
#include "stdin_input.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

/// Standard input copied into a private folder (mkdtemp: mode 0700, a fresh name) as its file
/// `input`; other names of the same file are hard links beside it. Removed with the object.
class StdinCopy {
 public:
  explicit StdinCopy(const std::string& option);
  ~StdinCopy();
  StdinCopy(const StdinCopy&) = delete;
  StdinCopy& operator=(const StdinCopy&) = delete;

  const std::string& path() const { return path_; }
  std::string with_extension(const std::string& extension);
  std::string named(std::string message) const;

 private:
  void copy_standard_input(const std::string& option);

  std::string folder_, path_;
  std::vector<std::string> other_names_;
};

StdinCopy::StdinCopy(const std::string& option) {
  std::string pattern = (fs::temp_directory_path() / "gridloc-stdin-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw Error(option + ": cannot make a folder for a copy of standard input in " +
                fs::temp_directory_path().string() + ": " + std::strerror(errno));
  }
  folder_ = pattern;
  path_ = folder_ + "/input";
  try {
    copy_standard_input(option);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
    throw;
  }
}

StdinCopy::~StdinCopy() {
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

/// Copies standard input to path_ in 64 KB blocks, stopping at --max-file-mb: a longer input
/// is refused before it can fill the disk or memory.
void StdinCopy::copy_standard_input(const std::string& option) {
  const int out = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (out < 0) throw Error(option + ": cannot copy standard input: " + std::strerror(errno));
  // check_input_file counts a file's size in whole MB (rounded up): the same bound here.
  const double limit_bytes = std::floor(limits().max_file_mb) * 1024.0 * 1024.0;
  double copied = 0.0;
  std::string problem;
  std::vector<char> block(1 << 16);
  while (problem.empty()) {
    const ssize_t got = ::read(STDIN_FILENO, block.data(), block.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) problem = std::string("cannot read standard input: ") + std::strerror(errno);
    if (got <= 0) break;
    copied += static_cast<double>(got);
    if (copied > limit_bytes) {
      std::ostringstream limit;
      limit << limits().max_file_mb;
      problem = "standard input is larger than the limit of " + limit.str() +
                " MB (raise it with " + LimitNames::file_mb + ")";
    } else if (::write(out, block.data(), static_cast<std::size_t>(got)) != got) {
      problem = std::string("cannot copy standard input: ") + std::strerror(errno);
    }
  }
  ::close(out);
  if (problem.empty() && copied == 0.0) problem = "standard input is empty";
  if (!problem.empty()) throw Error(option + ": " + problem);
}

std::string StdinCopy::with_extension(const std::string& extension) {
  const std::string other = path_ + extension;
  if (std::find(other_names_.begin(), other_names_.end(), other) != other_names_.end()) {
    return other;
  }
  std::error_code failed;
  fs::create_hard_link(path_, other, failed);
  if (failed) fs::copy_file(path_, other);  // a file system without hard links
  other_names_.push_back(other);
  return other;
}

std::string StdinCopy::named(std::string message) const {
  // The longer names first: each of them begins with path_.
  std::vector<std::string> names = other_names_;
  names.push_back(path_);
  for (const std::string& name : names) {
    for (auto at = message.find(name); at != std::string::npos; at = message.find(name, at)) {
      message.replace(at, name.size(), "standard input");
    }
  }
  return message;
}

/// The run's copy of standard input, made by the first input_path(kStdin, ...).
std::optional<StdinCopy>& run_copy() {
  static std::optional<StdinCopy> copy;
  return copy;
}

StdinCopy& existing_copy() {
  if (!run_copy()) throw Error("standard input has not been read (a gridloc bug)");
  return *run_copy();
}

/// The items of a comma-separated list option's value.
std::vector<std::string> list_items(const std::string& value) {
  std::vector<std::string> items;
  std::stringstream stream(value);
  std::string item;
  while (std::getline(stream, item, ',')) items.push_back(item);
  return items;
}

}  // namespace

void read_stdin_at_most_once(CLI::App* cmd, std::vector<InputOption> inputs) {
  cmd->parse_complete_callback([cmd, inputs = std::move(inputs)] {
    std::vector<std::string> readers;  // the options given `-`, once per `-`
    for (const InputOption& input : inputs) {
      for (const std::string& value : cmd->get_option(input.name)->results()) {
        const auto items = input.list ? list_items(value) : std::vector<std::string>{value};
        for (const std::string& item : items) {
          if (item == kStdin) readers.push_back(input.name);
        }
      }
    }
    if (readers.size() < 2) return;
    if (readers[0] == readers[1]) {
      throw Error(readers[0] +
                  " reads standard input (-) twice, but it can be read only once: give a file "
                  "instead");
    }
    throw Error(readers[0] + " and " + readers[1] +
                " both read standard input (-), but it can be read only once: give one of them "
                "a file");
  });
}

std::string input_path(const std::string& path, const std::string& option) {
  if (path != kStdin) return path;
  if (!run_copy()) run_copy().emplace(option);
  return run_copy()->path();
}

std::string stdin_path_with_extension(const std::string& extension) {
  return existing_copy().with_extension(extension);
}

std::string stdin_first_line(std::size_t max_bytes) {
  std::ifstream in(existing_copy().path(), std::ios::binary);
  std::string line(max_bytes, '\0');
  in.read(line.data(), static_cast<std::streamsize>(max_bytes));
  line.resize(static_cast<std::size_t>(in.gcount()));
  return line.substr(0, line.find('\n'));
}

std::string name_standard_input(std::string message) {
  return run_copy() ? run_copy()->named(std::move(message)) : message;
}

}  // namespace gridloc::cli
