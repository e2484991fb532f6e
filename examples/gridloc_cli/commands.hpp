#pragma once
// The gridloc subcommands; each registers its options and its action on the app.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "gridloc/engine/estimate.hpp"

namespace gridloc::cli {

struct GridDisambiguationSimulation;  // disambiguate_simulated.hpp
struct TeamSimulation;                // team_simulated.hpp

void add_localize(CLI::App& app);
void add_simulate(CLI::App& app);
void add_demo(CLI::App& app);
void add_eval(CLI::App& app);
void add_relations(CLI::App& app);
void add_map_from_log(CLI::App& app);
void add_heatmap(CLI::App& app);
void add_hallway(CLI::App& app);
void add_sectors(CLI::App& app);
void add_track(CLI::App& app);
/// `simulation` runs --pose on an occupancy map (the gridloc tool passes the evaluation's).
void add_disambiguate(CLI::App& app, const GridDisambiguationSimulation& simulation);
/// `simulation` runs --poses (the gridloc tool passes the team protocol's).
void add_team(CLI::App& app, const TeamSimulation& simulation);
void add_merge(CLI::App& app);

nlohmann::json to_json(const Pose2& pose);
/// A number, or null when it is NaN (an AUROC without failures, a rate of nothing).
nlohmann::json number_or_null(double value);
nlohmann::json to_json(const Estimate& estimate);

}  // namespace gridloc::cli
