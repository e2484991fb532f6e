// gridloc: localize a robot on a known map from a sonar ring (seed 001), simulate readings,
// run the demo and the paper's evaluation, draw tuning heatmaps, list a polygon map's visibility
// sectors. Errors print one line and exit with code 2.
#include <iostream>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"gridloc - occupancy-grid correlation localization from a sonar ring"};
  app.require_subcommand(1);
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
  gridloc::cli::add_disambiguate(app);
  gridloc::cli::add_team(app);
  gridloc::cli::add_track(app);
  gridloc::cli::add_merge(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "gridloc: error: " << e.what() << "\n";
    return 2;
  } catch (const gridloc::Error& e) {
    std::cerr << "gridloc: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "gridloc: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
