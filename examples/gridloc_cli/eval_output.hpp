#pragma once
// What `gridloc eval` writes for seed 001's protocol: the trials CSV, the JSON report and the
// table (cmd_eval.cpp declares the options and runs the protocol); the command line they echo.
#include <cstdint>
#include <string>
#include <vector>

#include "gridloc/engine/evaluation/sonar_protocol.hpp"
#include "localization_args.hpp"
#include "options.hpp"

namespace gridloc::cli {

/// The command line of `gridloc eval`.
struct EvalArgs {
  std::string maps, ring, noise = "realistic";
  bool maps_given = false;  ///< --maps was on the command line
  double step_xy = 0.1;     ///< the correlation's grid cell = translation step (m)
  SearchArgs search;
  FieldArgs field;
  std::string global_model;  ///< --global-model: only the oriented model on this grid
  OctomapArgs octomap;
  int trials = 100;
  std::uint64_t seed = 1;
  bool json = false;
  bool quiet = false;
  bool noisy = false;
  bool echo_filter = false;
  std::string trials_out;
  std::string calibration_plot;  ///< PNG of the coverage curves, or empty
  std::string estimators;        ///< empty: the correlation over the four model configurations
  LaserProtocol laser;
};

/// One line per trial and configuration: what calibration studies need.
void write_trials(const std::string& path, const EvalReport& report, const EvalOptions& options);

/// The calibration plot of every configuration's `localized` answers (issue 19):
/// calibration_render.hpp, `title` naming the run.
void write_calibration(const std::string& path, const EvalReport& report, const std::string& title);

/// Sonars the echo filter rejected, per trial (each trial's readings serve every configuration).
double mean_rejected_sonars(const EvalReport& report);

/// The report as JSON on stdout.
void print_json(const EvalArgs& args, const std::vector<EvalMap>& maps, const EvalReport& report,
                double rejected_per_trial);

/// The table's title lines: protocol, trials, search, noise, echo filter (and the laser).
void print_table_title(const EvalArgs& args, const EvalOptions& options, const SonarRing& ring,
                       std::size_t maps, const EvalReport& report, double rejected_per_trial);

/// One table row per configuration, under the column header, and the footnote.
void print_table_rows(const EvalReport& report);

}  // namespace gridloc::cli
