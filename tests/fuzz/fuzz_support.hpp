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

/// This process's scratch folder: /dev/shm (memory, no disk wear) when present, else the
/// system temp folder; created on first use and removed at exit. One per process, so fork
/// mode and parallel harnesses never share a file.
inline const fs::path& scratch_dir() {
  static const fs::path dir = [] {
    const fs::path base =
        fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    fs::path made = base / ("gridloc_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(made);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(scratch_dir(), ec);
    });
    return made;
  }();
  return dir;
}

/// Writes `size` bytes to `name` in the scratch folder (replacing it) and returns its path.
inline std::string write_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const fs::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path.string();
}

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
