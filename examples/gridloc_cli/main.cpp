// gridloc: localize a robot on a known map from a sonar ring (seed 001), simulate readings,
// run the demo and the paper's evaluation, draw tuning heatmaps, list a polygon map's visibility
// sectors. Errors print one line and exit with code 2.
#include <cctype>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "disambiguate_simulated.hpp"
#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"
#include "stdin_input.hpp"
#include "team_simulated.hpp"

namespace {

/// The commands, comma-separated, for the error lines below.
std::string command_list(const CLI::App& app) {
  std::string names;
  for (const CLI::App* command : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + command->get_name();
  }
  return names;
}

/// Why no command ran: the first word that is neither an option nor a number names an unknown
/// command, else none was given.
std::string missing_command(const CLI::App& app, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-' || std::isdigit(static_cast<unsigned char>(word[0]))) {
      continue;
    }
    return "unknown command '" + word + "'; the commands are: " + command_list(app);
  }
  return "no command given; the commands are: " + command_list(app);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gridloc - occupancy-grid correlation localization from a sonar ring"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("gridloc ") + GRIDLOC_VERSION);
  gridloc::cli::add_limit_options(app);
  gridloc::cli::add_localize(app);
  gridloc::cli::add_simulate(app);
  gridloc::cli::add_demo(app);
  gridloc::cli::add_eval(app);
  gridloc::cli::add_relations(app);
  gridloc::cli::add_map_from_log(app);
  gridloc::cli::add_hallway(app);
  gridloc::cli::add_heatmap(app);
  gridloc::cli::add_sectors(app);
  gridloc::cli::add_disambiguate(app, gridloc::cli::engine_loop_simulation());
  gridloc::cli::add_team(app, gridloc::cli::team_protocol_simulation());
  gridloc::cli::add_track(app);
  gridloc::cli::add_merge(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::RequiredError& e) {
    const bool no_command = app.get_subcommands().empty();
    std::cerr << "gridloc: error: " << (no_command ? missing_command(app, argc, argv) : e.what())
              << "\n";
    return 2;
  } catch (const CLI::ParseError& e) {
    std::cerr << "gridloc: error: " << e.what() << "\n";
    return 2;
  } catch (const gridloc::Error& e) {
    std::cerr << "gridloc: error: " << gridloc::cli::name_standard_input(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "gridloc: internal error: " << gridloc::cli::name_standard_input(e.what()) << "\n";
    return 1;
  }
  return 0;
}
