#pragma once
// The gridloc subcommands; each registers its options and its action on the app.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "gridloc/engine/estimate.hpp"

namespace gridloc::cli {

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
void add_disambiguate(CLI::App& app);
void add_team(CLI::App& app);
void add_merge(CLI::App& app);

nlohmann::json to_json(const Pose2& pose);
/// A number, or null when it is NaN (an AUROC without failures, a rate of nothing).
nlohmann::json number_or_null(double value);
nlohmann::json to_json(const Estimate& estimate);

}  // namespace gridloc::cli
