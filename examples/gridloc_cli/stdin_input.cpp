// Standard input as a file for the loaders (`--readings -`, `--scan -`).
#include "stdin_input.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"

namespace gridloc::cli {

StdinCopy::StdinCopy() {
  const auto dir = std::filesystem::temp_directory_path();
  path_ = (dir / ("gridloc-stdin-" + std::to_string(getpid()))).string();
  std::ofstream out(path_, std::ios::binary);
  if (!out) throw Error("standard input: cannot copy it to " + path_);
  const double limit_bytes = limits().max_file_mb * 1024.0 * 1024.0;
  char buffer[1 << 16];
  double copied = 0.0;
  while (std::cin.read(buffer, sizeof buffer) || std::cin.gcount() > 0) {
    copied += static_cast<double>(std::cin.gcount());
    if (copied > limit_bytes) {
      out.close();
      std::filesystem::remove(path_);
      throw Error("standard input: more than " + std::to_string(limits().max_file_mb) +
                  " MB (--max-file-mb)");
    }
    out.write(buffer, std::cin.gcount());
  }
}

StdinCopy::~StdinCopy() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

std::string StdinCopy::named(std::string message) const {
  for (auto at = message.find(path_); at != std::string::npos; at = message.find(path_)) {
    message.replace(at, path_.size(), "standard input");
  }
  return message;
}

}  // namespace gridloc::cli
