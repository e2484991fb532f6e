#pragma once
// gridloc eval's options, one group per concern, each registered by one function that every
// protocol's subcommand (and the old spelling) shares; `--help` shows each under its heading.
#include <CLI/CLI.hpp>
#include <string>

#include "eval_output.hpp"

namespace gridloc::cli {

/// --maps (comma-separated; `defaults` as its default, `help` saying what they are) and, with
/// `octomap`, --octomap-z-min and --octomap-z-max; group "Maps".
void add_map_options(CLI::App* cmd, EvalArgs& args, const std::string& defaults,
                     const std::string& help, bool octomap);

/// --trials (`help` saying what one is) and --seed; group "Trials".
void add_trial_options(CLI::App* cmd, EvalArgs& args, const std::string& help);

/// --json and --quiet, and with `trials_out` --trials-out; group "Output".
void add_output_options(CLI::App* cmd, EvalArgs& args, bool trials_out);

/// --calibration-plot (seed 001's protocol: sonar, laser); group "Output".
void add_calibration_plot_option(CLI::App* cmd, EvalArgs& args);

/// --ring, and with `noise` --noise (realistic | none); group "Sonar ring".
void add_ring_options(CLI::App* cmd, EvalArgs& args, bool noise);

/// --noisy and --echo-filter (seed 001's sonar protocol); group "Sonar ring".
void add_sonar_protocol_flags(CLI::App* cmd, EvalArgs& args);

/// --laser-beams, --laser-max-range and --laser-noise; group "Laser".
void add_laser_options(CLI::App* cmd, LaserProtocol& laser);

/// The correlation search's options and --step-xy, and with `models` --global-model and the
/// likelihood field's; group "Search".
void add_search_options(CLI::App* cmd, EvalArgs& args, bool models);

/// --estimators (`help` naming the ones that apply); group "Search".
void add_estimator_option(CLI::App* cmd, EvalArgs& args, const std::string& help);

/// Sets `group` as the heading of every option of `cmd` registered from index `first` on.
void set_group_from(CLI::App* cmd, std::size_t first, const std::string& group);

}  // namespace gridloc::cli
