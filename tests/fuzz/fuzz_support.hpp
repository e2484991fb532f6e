#pragma once
// Helpers shared by the libFuzzer harnesses: the fuzzed bytes written to a per-process file
// (the parsers take paths), and the error contract checked around each parser call.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "gridloc/grids/error.hpp"

namespace gridloc::fuzz {

namespace fs = std::filesystem;

/// A file of this process in /dev/shm (memory, no disk wear; the system temp folder when
/// /dev/shm is absent), `gridloc_fuzz_<pid>_<name>`, holding the fuzzed bytes and removed when
/// the run ends. Files, not a folder removed at exit: libFuzzer's fork-mode children end without
/// running exit handlers, and a crash leaves only the input it crashed on.
class ScratchFile {
 public:
  ScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size)
      : path_(folder() / file_name(name)) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
      std::fprintf(stderr, "fuzz harness: cannot write %s\n", path_.c_str());
      std::abort();
    }
  }
  ScratchFile(const std::string& name, std::string_view text)
      : ScratchFile(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size()) {}
  ~ScratchFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// The file's path, as a string.
  std::string path() const { return path_.string(); }
  /// The name this process gives `name` (unique per process, so parallel harnesses and fork
  /// mode's children never share a file).
  static std::string file_name(const std::string& name) {
    return "gridloc_fuzz_" + std::to_string(::getpid()) + "_" + name;
  }

 private:
  static fs::path folder() {
    return fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
  }
  fs::path path_;
};

/// The fuzzed bytes as text, for parsers that take a stream or a string.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs one parser call under the error contract: gridloc::Error is the expected answer to bad
/// input and is swallowed; any other exception is a finding, reported with its message and
/// turned into an abort so that libFuzzer saves the input.
template <class Call>
void expect_clean(Call&& call) {
  try {
    call();
  } catch (const Error&) {
    // The contract: one clear error for bad input.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz finding: exception other than gridloc::Error escaped: %s\n",
                 e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz finding: a non-std exception escaped\n");
    std::abort();
  }
}

}  // namespace gridloc::fuzz
