#pragma once
// The inputs of one localization, shared by `localize` and `heatmap`: the map, the sensor
// (sonar readings or a scan), the prior or --global, the window and the search options.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>

#include "gridloc/engine/correlation/estimator.hpp"
#include "options.hpp"

namespace gridloc::cli {

/// The likelihood field's parameters on the command line (--global-grid field): --field-sigma,
/// --field-cutoff and --field-free, shared by `localize`, `heatmap` and `eval`.
struct FieldArgs {
  LikelihoodFieldOptions field;

  /// Registers --field-sigma, --field-cutoff and --field-free.
  void add_to(CLI::App* cmd);
  /// Checks them (checked whatever the model: a bad number is a mistake even where unused)
  /// into options.field; throws gridloc::Error naming the option.
  void apply(CorrelationOptions& options) const;
};

struct LocalizationArgs {
  std::string map, ring, readings, scan, prior;
  double max_range = 8.0;
  std::string local = "oriented", global = "thinned";
  SearchArgs search;
  FieldArgs field;
  OctomapArgs octomap;
  SearchWindow window;
  int levels = 3;
  bool whole_map = false;  ///< --global
  /// --step-xy / --step-theta on the command line. A scan's defaults follow the map and the
  /// scan instead of seed 001's sonar lattice: the map's cell, and the heading step that
  /// moves the farthest return by half a cell (by one cell under --global, for speed).
  bool step_xy_given = false, step_theta_given = false;

  /// Registers --map, the OctoMap band, --ring, --readings, --scan, --max-range, --prior,
  /// --global (with `global_help`), the window, --local, --global-grid (alias
  /// --global-model), the field's options, --levels and the search options; the ring
  /// defaults to the bundled wheelchair ring.
  void add_to(CLI::App* cmd, const std::string& global_help);
};

/// What a command needs to localize: the observation, the estimator built for it, the
/// window (the global one under --global) and the estimator's construction time.
struct Localization {
  Observation observation;
  std::unique_ptr<CorrelationEstimator> estimator;
  SearchWindow window;
  double precompute_ms = 0.0;
  int firings = 0;  ///< sonar firings in the readings file (> 1: echo-filtered, see rejected)
};

/// Checks the arguments (one of --prior/--global, one of --readings/--scan; gridloc::Error
/// naming the option otherwise), loads the inputs and builds the estimator. A readings file
/// with several firings (firings_m) goes through the echo filter (filter_echoes): its
/// rejected sonars are in observation.rejected.
/// `tune`, when given, adjusts the estimator's options (their resolution is the window's
/// step) just before it is built.
Localization prepare_localization(const LocalizationArgs& args,
                                  const std::function<void(CorrelationOptions&)>& tune = {});

}  // namespace gridloc::cli
