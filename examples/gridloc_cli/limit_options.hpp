#pragma once
// The resource limits of the gridloc tool (issue 14): options of the main app that every
// subcommand accepts (`gridloc localize --max-cells 1e8 ...`), held for the run.
#include <CLI/CLI.hpp>

#include "gridloc/grids/limits.hpp"

namespace gridloc::cli {

/// The limits of this run: ResourceLimits' defaults, overridden by the --max-* options;
/// throws gridloc::Error naming a limit that is not a positive number.
const ResourceLimits& limits();

/// Adds --max-file-mb, --max-cells, --max-memory-mb, --max-beams, --max-vertices and
/// --max-coordinate-m to `app` (before the subcommands are added: they inherit them through
/// CLI11's fallthrough).
void add_limit_options(CLI::App& app);

}  // namespace gridloc::cli
