#include "gridloc/grids/limits.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/option_checks.hpp"

namespace gridloc {
namespace {

namespace fs = std::filesystem;

void check_positive(double value, const char* field) {
  require_positive(value, "resource limits", field);
}

}  // namespace

void ResourceLimits::validate() const {
  check_positive(max_file_mb, "max_file_mb");
  check_positive(max_cells, "max_cells");
  check_positive(max_memory_mb, "max_memory_mb");
  check_positive(max_beams, "max_beams");
  check_positive(max_vertices, "max_vertices");
  check_positive(max_coordinate_m, "max_coordinate_m");
}

void check_limit(double amount, double limit, const std::string& what, const std::string& unit,
                 const char* option) {
  if (amount <= limit) return;
  throw Error(what + ": " + message_number(amount) + " " + unit + " exceeds the limit of " +
              message_number(limit) + " " + unit + " (raise it with " + option + ")");
}

double check_grid_cells(double width, double height, const ResourceLimits& limits,
                        const std::string& what) {
  if (!(width >= 1.0) || !(height >= 1.0)) {
    throw Error(what + ": a grid of " + message_number(width) + " x " + message_number(height) +
                " cells is empty or not a number");
  }
  const double cells = width * height;
  check_limit(cells, limits.max_cells,
              what + " (" + message_number(width) + " x " + message_number(height) + ")", "cells",
              LimitNames::cells);
  constexpr double kIntMax = std::numeric_limits<int>::max();
  if (width > kIntMax || height > kIntMax) {
    throw Error(what + ": a side of " + message_number(std::max(width, height)) +
                " cells is too long");
  }
  return cells;
}

void check_memory(double bytes, const ResourceLimits& limits, const std::string& what) {
  const double mb = std::ceil(bytes / (1024.0 * 1024.0));
  if (mb <= limits.max_memory_mb) return;
  throw Error(what + " would need about " + message_number(mb) + " MB, more than the limit of " +
              message_number(limits.max_memory_mb) + " MB (raise it with " + LimitNames::memory_mb +
              ")");
}

std::uintmax_t check_input_file(const std::string& path, const std::string& what,
                                const ResourceLimits& limits) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw Error(path + ": " + what + " not found");
  if (fs::is_directory(status)) throw Error(path + ": is a directory, not a " + what);
  if (!fs::is_regular_file(status)) throw Error(path + ": not a regular file (a " + what + ")");
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) throw Error(path + ": cannot read the size of the " + what + ": " + ec.message());
  const double mb = std::ceil(static_cast<double>(bytes) / (1024.0 * 1024.0));
  if (mb > limits.max_file_mb) {
    throw Error(path + ": the " + what + " is " + message_number(mb) +
                " MB, more than the limit of " + message_number(limits.max_file_mb) +
                " MB (raise it with " + LimitNames::file_mb + ")");
  }
  return bytes;
}

std::string read_input_file(const std::string& path, const std::string& what,
                            const ResourceLimits& limits) {
  const std::uintmax_t bytes = check_input_file(path, what, limits);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the " + what + " for reading");
  std::string text(static_cast<std::size_t>(bytes), '\0');
  in.read(text.data(), static_cast<std::streamsize>(bytes));
  if (static_cast<std::uintmax_t>(in.gcount()) != bytes) {
    throw Error(path + ": the " + what + " could not be read whole");
  }
  return text;
}

}  // namespace gridloc
