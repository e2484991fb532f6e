#include "limit_options.hpp"

#include <cmath>
#include <string>

namespace gridloc::cli {
namespace {

ResourceLimits& mutable_limits() {
  static ResourceLimits run_limits;
  return run_limits;
}

/// A positive finite number, or CLI11's one-line error naming the option.
const CLI::Validator kPositive(
    [](const std::string& text) -> std::string {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !(value > 0.0) || !std::isfinite(value)) {
        return "must be a positive number, got '" + text + "'";
      }
      return "";
    },
    "POSITIVE");

}  // namespace

const ResourceLimits& limits() {
  mutable_limits().validate();
  return mutable_limits();
}

void add_limit_options(CLI::App& app) {
  ResourceLimits& run = mutable_limits();
  app.fallthrough();
  const auto add = [&](const char* name, double& field, const char* what) {
    app.add_option(name, field, what)
        ->check(kPositive)
        ->capture_default_str()
        ->group("Resource limits");
  };
  add(LimitNames::file_mb, run.max_file_mb, "Largest input file (MB)");
  add(LimitNames::cells, run.max_cells, "Largest grid gridloc builds (cells)");
  add(LimitNames::memory_mb, run.max_memory_mb, "Largest estimated memory of one map's grids (MB)");
  add(LimitNames::beams, run.max_beams, "Most beams or readings in one scan");
  add(LimitNames::vertices, run.max_vertices, "Most vertices of a polygon map");
  add(LimitNames::coordinate_m, run.max_coordinate_m,
      "Largest absolute coordinate of a map corner, origin or pose (m)");
}

}  // namespace gridloc::cli
