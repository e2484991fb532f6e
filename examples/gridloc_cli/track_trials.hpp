#pragma once
// The JSON of `gridloc track --trials` (issue 35): one line per trial, and the summary, which
// is computed from the trial lines alone so that `gridloc merge` rebuilds the very summary
// one process prints from its shards' lines.
#include <nlohmann/json.hpp>
#include <vector>

#include "gridloc/engine/evaluation/log_tracking.hpp"

namespace gridloc::cli {

/// One trial's JSON line: its number, start, the standstill and drive answers.
nlohmann::json trial_json(const GlobalTrial& trial, const GlobalTrialOptions& options);

/// The summary of trial lines (trial_json's), in trial order: success and wrong-localized
/// shares from the standstill and after the drive, the mean path to the first `localized`.
nlohmann::json trials_summary(const std::vector<nlohmann::json>& trials);

}  // namespace gridloc::cli
