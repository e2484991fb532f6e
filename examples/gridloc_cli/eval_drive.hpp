#pragma once
// `gridloc eval --drive D`: the drive protocol (engine/evaluation/drive_protocol.hpp), a
// short drive's fused firings against the last firing alone, as a table or JSON.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "eval_output.hpp"

namespace gridloc::cli {

/// The drive protocol's options of `gridloc eval` (off without --drive).
struct DriveArgs {
  double drive_m = 0.0;
  int firings = 5;
  std::string odometry_noise = "0.02,1";  ///< FRAC,DEG_PER_M
  bool windowed = false;                  ///< a prior window instead of global search
  double window_m = 2.0;                  ///< DriveWindowOptions::max_distance_m
  bool given = false;                     ///< --drive was on the command line
};

/// Registers --drive, --drive-firings, --odometry-noise, --drive-windowed, --drive-window-m.
void add_drive_options(CLI::App* cmd, DriveArgs& drive);

/// Runs the drive protocol on `files` with `args`' trials, seed, noise and search; prints
/// the table (with a progress line) or JSON.
void run_drive_eval(const EvalArgs& args, const DriveArgs& drive,
                    const std::vector<std::string>& files);

}  // namespace gridloc::cli
