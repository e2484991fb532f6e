// gridloc eval PROTOCOL: one subcommand per evaluation protocol (sonar, laser, drive, sectors,
// disambiguation, team), each with only its options, drawn from shared groups
// (eval_option_groups.hpp); eval_protocols.cpp runs them. The old spelling (`gridloc eval`
// with --laser, --drive D, --protocol P, polygon maps or a sector estimator) keeps working:
// its options stay on `gridloc eval`, out of its --help, and a run prints the new spelling.
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "eval_option_groups.hpp"
#include "eval_protocols.hpp"
#include "gridloc/grids/error.hpp"
#include "old_spelling.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

/// What one eval command parses into.
struct EvalCommandArgs {
  EvalArgs args;
  DriveArgs drive;
  ProtocolArgs protocol;
};

std::shared_ptr<EvalCommandArgs> default_args() {
  auto command = std::make_shared<EvalCommandArgs>();
  command->args.ring = data_dir() + "/sensors/wheelchair_14.yaml";
  return command;
}

const std::string kGridMapsHelp =
    "comma-separated bundled map names, YAML paths or OctoMap .bt/.ot paths (one may be -: "
    "standard input)";
const std::string kAnyMapsHelp =
    "comma-separated bundled map names or YAML paths, polygon or occupancy maps (one may be "
    "-: standard input)";

/// A value as the shell reads it back.
std::string shell_word(const std::string& value) {
  if (!value.empty() &&
      value.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                              "_+-=.,/:@%") == std::string::npos) {
    return value;
  }
  std::string quoted = "'";
  for (const char c : value) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The new spelling of an old-spelling run: `gridloc eval PROTOCOL` and each option given
/// that the protocol's command has (the others had no effect), renamed where it names it
/// otherwise.
std::string new_spelling(CLI::App& cmd, EvalProtocol protocol) {
  static const std::map<std::string, std::string> renamed = {{"drive", "--distance"},
                                                             {"drive-firings", "--firings"},
                                                             {"drive-windowed", "--windowed"},
                                                             {"drive-window-m", "--window-m"},
                                                             {"protocol", ""},
                                                             {"laser", ""}};
  std::string line = "gridloc eval " + protocol_name(protocol);
  const CLI::App* protocol_command = cmd.get_subcommand(protocol_name(protocol));
  for (const CLI::Option* option : cmd.get_options()) {
    if (option->count() == 0 || option->get_lnames().empty()) continue;
    const std::string& long_name = option->get_lnames().front();
    const auto rename = renamed.find(long_name);
    const std::string name = rename == renamed.end() ? "--" + long_name : rename->second;
    if (name.empty() || !protocol_command->get_option_no_throw(name)) continue;
    line += " " + name;
    if (option->get_expected_max() == 0) continue;  // a flag
    std::string values;
    for (const std::string& value : option->results())
      values += (values.empty() ? "" : ",") + value;
    line += " " + shell_word(values);
  }
  return line;
}

/// Throws when options of `gridloc eval` itself came before the protocol's name.
void refuse_options_before(const CLI::App& eval, const std::string& protocol) {
  for (const CLI::Option* option : eval.get_options()) {
    if (option->count() == 0 || option->get_lnames().empty()) continue;
    throw Error("gridloc eval " + protocol + ": options follow the protocol (gridloc eval " +
                protocol + " --" + option->get_lnames().front() + " ...), got --" +
                option->get_lnames().front() + " before it");
  }
}

/// Registers `gridloc eval NAME`, its options from `add`, and its run.
template <class AddOptions>
void add_protocol(CLI::App* eval, EvalProtocol protocol, const std::string& description,
                  AddOptions add) {
  auto command = default_args();
  CLI::App* cmd = eval->add_subcommand(protocol_name(protocol), description);
  cmd->fallthrough(false);  // the old spelling's options on `gridloc eval` are not its
  add(cmd, *command);
  cmd->callback([eval, protocol, command] {
    refuse_options_before(*eval, protocol_name(protocol));
    run_protocol(protocol, command->args, command->drive, command->protocol);
  });
}

void add_grid_protocols(CLI::App* eval) {
  const std::string estimators =
      "compare these estimators on the same trials: comma-separated correlation, icp, "
      "correlation+icp (icp needs the laser); default: the correlation over {turned, oriented} "
      "x {raw, thinned}";
  add_protocol(eval, EvalProtocol::Sonar,
               "seed 001's protocol with the sonar ring: random poses on grid maps, a prior "
               "window each",
               [&](CLI::App* cmd, EvalCommandArgs& c) {
                 add_map_options(cmd, c.args, kRoomMaps, kGridMapsHelp, true);
                 add_trial_options(cmd, c.args, "random poses per map");
                 add_ring_options(cmd, c.args, true);
                 add_sonar_protocol_flags(cmd, c.args);
                 add_search_options(cmd, c.args, true);
                 add_estimator_option(cmd, c.args, estimators);
                 add_output_options(cmd, c.args, true);
                 add_calibration_plot_option(cmd, c.args);
                 read_stdin_at_most_once(cmd, {{"--maps", true}, {"--ring"}});
               });
  add_protocol(eval, EvalProtocol::Laser,
               "seed 001's protocol with a simulated 360 degree laser instead of the ring",
               [&](CLI::App* cmd, EvalCommandArgs& c) {
                 add_map_options(cmd, c.args, kRoomMaps, kGridMapsHelp, true);
                 add_trial_options(cmd, c.args, "random poses per map");
                 add_laser_options(cmd, c.args.laser);
                 add_search_options(cmd, c.args, true);
                 add_estimator_option(cmd, c.args, estimators);
                 add_output_options(cmd, c.args, true);
                 add_calibration_plot_option(cmd, c.args);
                 read_stdin_at_most_once(cmd, {{"--maps", true}});
               });
  add_protocol(eval, EvalProtocol::Drive,
               "the drive protocol: a short drive's fused firings against the last firing "
               "alone, with the sonar ring",
               [](CLI::App* cmd, EvalCommandArgs& c) {
                 add_map_options(cmd, c.args, kRoomMaps, kGridMapsHelp, true);
                 add_trial_options(cmd, c.args, "random poses per map");
                 const std::size_t first = cmd->get_options().size();
                 add_drive_protocol_options(cmd, c.drive);
                 set_group_from(cmd, first, "Drive");
                 add_ring_options(cmd, c.args, true);
                 add_search_options(cmd, c.args, false);
                 add_output_options(cmd, c.args, false);
                 read_stdin_at_most_once(cmd, {{"--maps", true}, {"--ring"}});
               });
}

void add_other_protocols(CLI::App* eval) {
  add_protocol(eval, EvalProtocol::Sectors,
               "the sector protocol: polygon maps, 360 degree scans, no prior; the sector "
               "estimators against the correlation search",
               [](CLI::App* cmd, EvalCommandArgs& c) {
                 add_map_options(cmd, c.args, kPolygonMaps,
                                 "comma-separated bundled polygon map names or polygon YAML "
                                 "paths (one may be -: standard input)",
                                 false);
                 add_trial_options(cmd, c.args, "random poses per map");
                 add_laser_options(cmd, c.args.laser);
                 add_search_options(cmd, c.args, false);
                 add_estimator_option(cmd, c.args,
                                      "comma-separated: sectors, sectors+correlation, correlation "
                                      "(default: sectors and correlation)");
                 add_output_options(cmd, c.args, true);
                 read_stdin_at_most_once(cmd, {{"--maps", true}});
               });
  add_protocol(eval, EvalProtocol::Disambiguation,
               "seed 002's minimum-distance protocol on random offices, or with --sensor the "
               "engine in the loop on --maps",
               [](CLI::App* cmd, EvalCommandArgs& c) {
                 const std::size_t first = cmd->get_options().size();
                 add_disambiguation_options(cmd, c.protocol.disambiguation, false);
                 set_group_from(cmd, first, "Disambiguation");
                 add_map_options(cmd, c.args, kDisambiguationMaps,
                                 "--sensor: comma-separated bundled occupancy map names or YAML "
                                 "paths (one may be -: standard input)",
                                 false);
                 add_trial_options(cmd, c.args, "--sensor: ambiguous starts per map");
                 add_ring_options(cmd, c.args, false);
                 add_laser_options(cmd, c.args.laser);
                 add_output_options(cmd, c.args, false);
                 read_stdin_at_most_once(cmd, {{"--maps", true}, {"--ring"}});
               });
  add_protocol(eval, EvalProtocol::Team,
               "seed 003's team protocol: random linked teams of each size on each map",
               [](CLI::App* cmd, EvalCommandArgs& c) {
                 const std::size_t first = cmd->get_options().size();
                 add_team_options(cmd, c.protocol.team, false);
                 cmd->add_option("--sensor", c.protocol.disambiguation.sensor,
                                 "ir (default) | laser | sonar")
                     ->check(CLI::IsMember({"ir", "laser", "sonar"}));
                 set_group_from(cmd, first, "Team");
                 add_map_options(cmd, c.args, kTeamMaps, kAnyMapsHelp, false);
                 add_trial_options(cmd, c.args, "random teams per size and map");
                 add_ring_options(cmd, c.args, false);
                 add_laser_options(cmd, c.args.laser);
                 add_output_options(cmd, c.args, false);
                 read_stdin_at_most_once(cmd, {{"--maps", true}, {"--ring"}});
               });
}

/// The old spelling: every protocol's options on `gridloc eval` itself, the protocol told by
/// --protocol, --drive, --laser, the maps and the estimators.
void add_old_spelling(CLI::App* cmd) {
  auto command = default_args();
  EvalArgs& args = command->args;
  add_map_options(cmd, args, kRoomMaps,
                  kGridMapsHelp + "; polygon maps run the sector protocol (default there: " +
                      std::string(kPolygonMaps) + ")",
                  true);
  add_ring_options(cmd, args, true);
  add_trial_options(cmd, args, "random poses per map");
  add_search_options(cmd, args, true);
  add_output_options(cmd, args, true);
  add_calibration_plot_option(cmd, args);
  add_sonar_protocol_flags(cmd, args);
  add_estimator_option(cmd, args,
                       "compare these estimators on the same trials: comma-separated "
                       "correlation, icp, correlation+icp (icp needs --laser), sectors, "
                       "sectors+correlation (the sector protocol)");
  cmd->add_flag("--laser", args.laser.enabled,
                "observe with a simulated 360 degree laser instead of the sonar ring");
  add_laser_options(cmd, args.laser);
  add_drive_options(cmd, command->drive);
  cmd->add_option("--protocol", command->protocol.name, "disambiguation | team")
      ->check(CLI::IsMember({"disambiguation", "team"}));
  add_disambiguation_options(cmd, command->protocol.disambiguation, true);
  add_team_options(cmd, command->protocol.team, true);
  set_group_from(cmd, 1, kOldSpelling);  // all but --help
  read_stdin_at_most_once(cmd, {{"--maps", true}, {"--ring"}});
  cmd->callback([cmd, command] {
    if (!cmd->get_subcommands().empty()) return;  // `gridloc eval PROTOCOL` ran
    const EvalProtocol protocol =
        old_spelling_protocol(command->args, command->drive, command->protocol);
    run_protocol(protocol, command->args, command->drive, command->protocol);
    if (!command->args.quiet) {
      std::cerr << "gridloc eval: this spelling keeps working; its protocol's own command is: "
                << new_spelling(*cmd, protocol) << "\n";
    }
  });
}

}  // namespace

void add_eval(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Run an evaluation protocol and print its table or JSON: gridloc eval PROTOCOL [options] "
      "(gridloc eval PROTOCOL --help lists its options). The old spelling, gridloc eval "
      "[--laser | --drive D | --protocol P] [options], keeps working and prints the new one");
  cmd->require_subcommand(0, 1);
  add_grid_protocols(cmd);
  add_other_protocols(cmd);
  add_old_spelling(cmd);
  hide_old_spellings(cmd);
}

}  // namespace gridloc::cli
