// gridloc track --trials: a trial's JSON line and the summary of the lines.
#include "track_trials.hpp"

#include <cmath>

#include "commands.hpp"

namespace gridloc::cli {
namespace {

/// The verdict and error of one answer, for a trial's JSON.
nlohmann::json answer_json(const TrackStep& step, const GlobalTrialOptions& options) {
  return {{"index", step.index},           {"verdict", to_string(step.estimate.verdict)},
          {"right", right(step, options)}, {"error_m", step.error_m},
          {"error_deg", step.error_deg},   {"travelled_m", step.travelled_m},
          {"timing_ms", step.timing_ms}};
}

/// `localized` beyond the trials' tolerances.
bool wrong(const nlohmann::json& answer) {
  return answer.at("verdict") == "localized" && !answer.at("right").get<bool>();
}

}  // namespace

nlohmann::json trial_json(const GlobalTrial& trial, const GlobalTrialOptions& options) {
  return {{"trial", trial.trial},
          {"start", trial.start},
          {"standstill", answer_json(trial.standstill, options)},
          {"end", answer_json(trial.end, options)},
          {"localized_after_m", number_or_null(trial.localized_after_m.value_or(std::nan("")))},
          {"wrong_localized", trial.wrong_localized}};
}

nlohmann::json trials_summary(const std::vector<nlohmann::json>& trials) {
  int standstill_right = 0, standstill_wrong = 0, end_right = 0, end_wrong = 0, localized = 0;
  double localized_after_m = 0.0;
  for (const nlohmann::json& trial : trials) {
    standstill_right += trial.at("standstill").at("right").get<bool>();
    standstill_wrong += wrong(trial.at("standstill"));
    end_right += trial.at("end").at("right").get<bool>();
    end_wrong += wrong(trial.at("end"));
    if (!trial.at("localized_after_m").is_null()) {
      ++localized;
      localized_after_m += trial.at("localized_after_m").get<double>();
    }
  }
  const int count = static_cast<int>(trials.size());
  const auto share = [count](int n) { return count > 0 ? 100.0 * n / count : 0.0; };
  return {{"trials", count},
          {"standstill_success_pct", share(standstill_right)},
          {"standstill_localized_wrong_pct", share(standstill_wrong)},
          {"drive_success_pct", share(end_right)},
          {"drive_localized_wrong_pct", share(end_wrong)},
          {"mean_localized_after_m",
           number_or_null(localized > 0 ? localized_after_m / localized : std::nan(""))}};
}

}  // namespace gridloc::cli
