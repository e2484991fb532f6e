// gridloc merge: joins the JSON Lines of `gridloc track --trials N --shard K/N --json` runs
// (issue 35) into what one process prints: every trial line in trial order, then the summary
// rebuilt from them. Refuses shards of different runs, a missing or repeated shard or trial,
// and a shard that did not finish (no summary line).
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"
#include "stdin_input.hpp"
#include "track_trials.hpp"

namespace gridloc::cli {
namespace {

/// One shard's output: its trial lines and what its summary says of the shard.
struct ShardOutput {
  std::vector<nlohmann::json> trials;
  int index = 0, count = 0, total = 0;  ///< K, N and the whole run's --trials
};

int shard_field(const nlohmann::json& shard, const char* key, const std::string& path) {
  if (!shard.contains(key) || !shard[key].is_number_integer()) {
    throw Error(path + ": its summary's shard has no integer '" + key + "'");
  }
  return shard[key].get<int>();
}

/// Whether `line` has what the summary counts (trials_summary's fields).
bool is_trial_line(const nlohmann::json& line) {
  const auto answer = [&](const char* key) {
    return line.contains(key) && line[key].is_object() && line[key].contains("right") &&
           line[key]["right"].is_boolean() && line[key].contains("verdict") &&
           line[key]["verdict"].is_string();
  };
  return line.contains("trial") && line["trial"].is_number_integer() &&
         line["trial"].get<int>() >= 0 && answer("standstill") && answer("end") &&
         line.contains("localized_after_m") &&
         (line["localized_after_m"].is_null() || line["localized_after_m"].is_number());
}

/// Reads a shard's JSON Lines; throws naming the file (and line) when it is not one.
ShardOutput read_shard(const std::string& path) {
  std::istringstream text(
      read_input_file(input_path(path, "files"), "shard output (JSON Lines)", limits()));
  ShardOutput shard;
  bool summary = false;
  std::string line;
  for (int number = 1; std::getline(text, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const nlohmann::json parsed = nlohmann::json::parse(line, nullptr, false);
    if (parsed.is_discarded() || !parsed.is_object()) {
      throw Error(path + ":" + std::to_string(number) + ": not a JSON object");
    }
    if (parsed.contains("trial")) {
      if (!is_trial_line(parsed)) {
        throw Error(path + ":" + std::to_string(number) +
                    ": a trial line without its number, answers or localized_after_m");
      }
      shard.trials.push_back(parsed);
    } else if (parsed.contains("summary")) {
      if (!parsed.contains("shard") || !parsed["shard"].is_object()) {
        throw Error(path +
                    ": not a shard (its summary names no shard: run track --trials N "
                    "--shard K/N --json)");
      }
      shard.index = shard_field(parsed["shard"], "index", path);
      shard.count = shard_field(parsed["shard"], "count", path);
      shard.total = shard_field(parsed["shard"], "trials", path);
      summary = true;
    } else {
      throw Error(path + ":" + std::to_string(number) + ": neither a trial nor a summary line");
    }
  }
  if (!summary) throw Error(path + ": no summary line (the shard did not finish)");
  return shard;
}

/// Every shard 1..N once, of one run (the same N and --trials), and every trial once.
std::vector<nlohmann::json> merged_trials(const std::vector<std::string>& paths) {
  std::map<int, std::string> shards;  // K -> its file
  std::map<int, nlohmann::json> trials;
  int count = 0, total = 0;
  for (const std::string& path : paths) {
    ShardOutput shard = read_shard(path);
    if (shards.empty()) count = shard.count, total = shard.total;
    if (shard.count != count || shard.total != total) {
      throw Error(path + ": shard of " + std::to_string(shard.total) + " trials in " +
                  std::to_string(shard.count) + " shards, " + paths.front() + " of " +
                  std::to_string(total) + " in " + std::to_string(count) + ": not one run");
    }
    if (!shards.emplace(shard.index, path).second) {
      throw Error(path + ": shard " + std::to_string(shard.index) + " is also " +
                  shards[shard.index]);
    }
    for (nlohmann::json& trial : shard.trials) {
      const int t = trial["trial"].get<int>();
      if (!trials.emplace(t, std::move(trial)).second) {
        throw Error(path + ": trial " + std::to_string(t) + " appears twice");
      }
    }
  }
  for (int k = 1; k <= count; ++k) {
    if (!shards.count(k))
      throw Error("shard " + std::to_string(k) + "/" + std::to_string(count) + " is missing");
  }
  if (static_cast<int>(trials.size()) != total) {
    throw Error("the shards hold " + std::to_string(trials.size()) + " trials, the run has " +
                std::to_string(total));
  }
  std::vector<nlohmann::json> ordered;
  for (auto& [t, trial] : trials) ordered.push_back(std::move(trial));
  return ordered;
}

void run(const std::vector<std::string>& paths) {
  const std::vector<nlohmann::json> trials = merged_trials(paths);
  for (const nlohmann::json& trial : trials) std::cout << trial.dump() << "\n";
  std::cout << nlohmann::json{{"summary", trials_summary(trials)}}.dump() << "\n";
}

}  // namespace

void add_merge(CLI::App& app) {
  auto paths = std::make_shared<std::vector<std::string>>();
  auto* cmd = app.add_subcommand(
      "merge",
      "Join the --json outputs of `track --trials N --shard K/N` (every shard once) into what "
      "one process prints: the trials in order and their summary");
  cmd->add_option("files", *paths, "the shards' JSON Lines files (one may be -: standard input)")
      ->required();
  read_stdin_at_most_once(cmd, {{"files"}});
  cmd->callback([paths] { run(*paths); });
}

}  // namespace gridloc::cli
