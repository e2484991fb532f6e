// gridloc eval's option groups (eval_option_groups.hpp).
#include "eval_option_groups.hpp"

namespace gridloc::cli {

void set_group_from(CLI::App* cmd, std::size_t first, const std::string& group) {
  std::vector<CLI::Option*> options = cmd->get_options();
  for (std::size_t k = first; k < options.size(); ++k) options[k]->group(group);
}

void add_map_options(CLI::App* cmd, EvalArgs& args, const std::string& defaults,
                     const std::string& help, bool octomap) {
  const std::size_t first = cmd->get_options().size();
  args.maps = defaults;
  cmd->add_option("--maps", args.maps, help)
      ->capture_default_str()
      ->each([&args](const std::string&) { args.maps_given = true; });
  if (octomap) args.octomap.add_to(cmd);
  set_group_from(cmd, first, "Maps");
}

void add_trial_options(CLI::App* cmd, EvalArgs& args, const std::string& help) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_option("--trials", args.trials, help)->capture_default_str();
  cmd->add_option("--seed", args.seed, "seed of poses, priors and noise")->capture_default_str();
  set_group_from(cmd, first, "Trials");
}

void add_output_options(CLI::App* cmd, EvalArgs& args, bool trials_out) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_flag("--json", args.json, "print JSON instead of the table");
  cmd->add_flag("--quiet", args.quiet, "no progress line");
  if (trials_out) {
    cmd->add_option("--trials-out", args.trials_out,
                    "write every trial (errors, scores, confidence, std) to this CSV");
  }
  set_group_from(cmd, first, "Output");
}

void add_calibration_plot_option(CLI::App* cmd, EvalArgs& args) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_option("--calibration-plot", args.calibration_plot,
                  "write F.png: for each configuration, the share of its localized answers "
                  "whose position error lies within the covariance's p ellipse, against p");
  set_group_from(cmd, first, "Output");
}

void add_ring_options(CLI::App* cmd, EvalArgs& args, bool noise) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_option("--ring", args.ring, "sonar ring YAML (- reads standard input)")
      ->capture_default_str();
  if (noise) cmd->add_option("--noise", args.noise, "realistic | none")->capture_default_str();
  set_group_from(cmd, first, "Sonar ring");
}

void add_sonar_protocol_flags(CLI::App* cmd, EvalArgs& args) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_flag("--noisy", args.noisy,
                "the calibration protocol: harsh noise (3 cm + 2 %, 5 % dropouts and "
                "crosstalk, specular beyond 60 deg), 15 % wrong priors, 25 % furniture changes");
  cmd->add_flag("--echo-filter", args.echo_filter,
                "fire the ring 3 times per trial and reject sonars whose echoes disagree "
                "(EERUF-like; a rejected sonar adds nothing to the local grid)");
  set_group_from(cmd, first, "Sonar ring");
}

void add_laser_options(CLI::App* cmd, LaserProtocol& laser) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_option("--laser-beams", laser.beams, "laser beams per scan")->capture_default_str();
  cmd->add_option("--laser-max-range", laser.max_range, "laser max range (m)")
      ->capture_default_str();
  cmd->add_option("--laser-noise", laser.sigma_m, "laser range noise sigma (m)")
      ->capture_default_str();
  set_group_from(cmd, first, "Laser");
}

void add_search_options(CLI::App* cmd, EvalArgs& args, bool models) {
  const std::size_t first = cmd->get_options().size();
  args.search.add_to(cmd);
  if (models) {
    cmd->add_option("--global-model,--global-grid", args.global_model,
                    "run only the oriented local grid (or each of --estimators) on this global "
                    "grid: thinned | raw | field (likelihood field, see --field-sigma)");
    args.field.add_to(cmd);
  }
  cmd->add_option("--step-xy", args.step_xy,
                  "the correlation search's grid cell and translation step (m; seed 001: 0.1)")
      ->capture_default_str();
  set_group_from(cmd, first, "Search");
}

void add_estimator_option(CLI::App* cmd, EvalArgs& args, const std::string& help) {
  const std::size_t first = cmd->get_options().size();
  cmd->add_option("--estimators,--estimator", args.estimators, help);
  set_group_from(cmd, first, "Search");
}

}  // namespace gridloc::cli
