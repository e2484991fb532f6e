#pragma once
// gridloc eval's sector protocol (issue 6): polygon maps, global 360-degree scans, the sector
// estimators against the correlation search on the same trials.
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/sector_protocol.hpp"

namespace gridloc::cli {

struct SectorEvalArgs {
  std::vector<std::string> maps;  ///< polygon map files
  SectorEvalOptions options;
  bool json = false;
  bool quiet = false;
  std::string trials_out;  ///< CSV of every trial, or empty
};

/// Runs the protocol and prints its table (or JSON with --json) to stdout, progress to stderr.
void run_sector_eval(const SectorEvalArgs& args);

}  // namespace gridloc::cli
