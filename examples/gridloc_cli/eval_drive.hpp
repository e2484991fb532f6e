#pragma once
// `gridloc eval --drive D`: the drive protocol (engine/evaluation/drive_protocol.hpp), a
// short drive's fused firings against the last firing alone, as a table or JSON.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "eval_output.hpp"

namespace gridloc::cli {

/// The drive protocol's options (the old spelling's are off without --drive).
struct DriveArgs {
  double drive_m = 0.0;
  int firings = 5;
  std::string odometry_noise = "0.02,1";  ///< FRAC,DEG_PER_M
  bool windowed = false;                  ///< a prior window instead of global search
  double window_m = 2.0;                  ///< DriveWindowOptions::max_distance_m
  bool given = false;                     ///< --drive was on the command line
  /// The options' names in errors: the old spelling's (`gridloc eval --drive D`) or
  /// `gridloc eval drive`'s.
  std::string distance_option = "--drive", firings_option = "--drive-firings",
              window_option = "--drive-window-m";
};

/// Registers the old spelling's --drive, --drive-firings, --odometry-noise, --drive-windowed,
/// --drive-window-m on `gridloc eval`.
void add_drive_options(CLI::App* cmd, DriveArgs& drive);

/// Registers `gridloc eval drive`'s --distance (default 2 m), --firings, --odometry-noise,
/// --windowed and --window-m; the protocol is on.
void add_drive_protocol_options(CLI::App* cmd, DriveArgs& drive);

/// Runs the drive protocol on `files` with `args`' trials, seed, noise and search; prints
/// the table (with a progress line) or JSON.
void run_drive_eval(const EvalArgs& args, const DriveArgs& drive,
                    const std::vector<std::string>& files);

}  // namespace gridloc::cli
