#pragma once
/// `-` for standard input wherever the CLI reads a readings file or a scan: standard input is
/// copied to a temporary file (at most the --max-file-mb limit) that the loaders read, and
/// their errors name standard input instead of the copy.
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc::cli {

/// Runs `load(path)`; for "-" it loads a copy of standard input instead.
template <class Load>
auto load_input(const std::string& path, Load&& load) -> decltype(load(path));

/// A copy of standard input in a temporary file, removed with the object.
class StdinCopy {
 public:
  StdinCopy();
  ~StdinCopy();
  StdinCopy(const StdinCopy&) = delete;
  StdinCopy& operator=(const StdinCopy&) = delete;
  const std::string& path() const { return path_; }
  /// `message` with the copy's path replaced by "standard input".
  std::string named(std::string message) const;

 private:
  std::string path_;
};

template <class Load>
auto load_input(const std::string& path, Load&& load) -> decltype(load(path)) {
  if (path != "-") return load(path);
  const StdinCopy copy;
  try {
    return load(copy.path());
  } catch (const Error& e) {
    throw Error(copy.named(e.what()));
  }
}

}  // namespace gridloc::cli
