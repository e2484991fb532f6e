// gridloc eval on polygon maps: the sector protocol's table, JSON and per-trial CSV.
#include "eval_sectors.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "progress.hpp"

namespace gridloc::cli {
namespace {

/// One line per trial and estimator.
void write_trials(const std::string& path, const SectorEvalReport& report,
                  const SectorEvalOptions& options) {
  std::ofstream out(path);
  if (!out) throw Error("--trials-out: cannot write " + path);
  out << "map,trial,estimator,truth_x,truth_y,truth_theta,true_sector,found_sector,"
         "ambiguous_label,success,position_error_m,heading_error_deg,confidence,verdict,ms\n";
  for (const SectorTrialRecord& r : report.records) {
    const Estimate& e = r.estimate;
    out << r.map << ',' << r.trial << ',' << to_string(options.estimators[r.estimator]) << ','
        << r.truth.x << ',' << r.truth.y << ',' << r.truth.theta << ',' << r.true_sector << ','
        << r.found_sector << ',' << r.ambiguous_label << ',' << r.success << ','
        << r.position_error_m << ',' << r.heading_error_deg << ',' << e.confidence << ','
        << to_string(e.verdict) << ',' << e.stats.elapsed_ms << '\n';
  }
  if (!out) throw Error("--trials-out: writing " + path + " failed");
}

/// `v` as a percentage table cell, "-" for NaN.
std::string percent_or_dash(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * v);
  return buf;
}

/// One estimator's result as JSON.
nlohmann::json result_json(const SectorEvalResult& r) {
  return {{"estimator", to_string(r.estimator)},
          {"success_rate", r.success_rate},
          {"successes", r.successes},
          {"sector_identification_rate", r.sector_identification_rate},
          {"sectors_identified", r.sector_identified},
          {"mean_position_error_m", r.mean_position_error_m},
          {"mean_heading_error_deg", r.mean_heading_error_deg},
          {"median_position_error_m", number_or_null(r.median_position_error_m)},
          {"median_heading_error_deg", number_or_null(r.median_heading_error_deg)},
          {"median_ms", r.median_ms},
          {"localized", r.localized},
          {"ambiguous", r.ambiguous},
          {"not_localized", r.not_localized},
          {"false_fixes", r.false_fixes},
          {"ambiguous_label_trials", r.ambiguous_label_trials},
          {"ambiguity_detected", r.ambiguity_detected},
          {"ambiguity_answered_wrongly", r.ambiguity_answered_wrongly},
          {"ambiguity_detection_rate", number_or_null(r.ambiguity_detection_rate)}};
}

/// The report as JSON on stdout.
void print_json(const std::vector<SectorEvalMap>& maps, const SectorEvalOptions& options,
                const SectorEvalReport& report) {
  nlohmann::json configs = nlohmann::json::array();
  for (const SectorEvalResult& r : report.results) configs.push_back(result_json(r));
  nlohmann::json names = nlohmann::json::array();
  for (const auto& m : maps) names.push_back(m.name);
  std::cout << nlohmann::json{{"protocol", "sectors"},
                              {"trials", report.trials},
                              {"maps", names},
                              {"sectors_per_map", report.sectors_per_map},
                              {"ambiguous_sectors_per_map", report.ambiguous_sectors_per_map},
                              {"seed", options.seed},
                              {"sensor", "laser"},
                              {"beams", options.beams},
                              {"max_range_m", options.max_range},
                              {"laser_noise_m", options.sigma_m},
                              {"prior", nullptr},
                              {"configurations", configs}}
                   .dump(2)
            << "\n";
}

/// The table's title lines: the protocol, then each map's sectors.
void print_table_title(const std::vector<SectorEvalMap>& maps, const SectorEvalOptions& options,
                       const SectorEvalReport& report) {
  std::printf(
      "sector protocol: %d trials (%zu polygon maps), seed %llu, %d-beam 360 deg scans (%.1f m "
      "max range, %.3f m noise), no prior\n",
      report.trials, maps.size(), static_cast<unsigned long long>(options.seed), options.beams,
      options.max_range, options.sigma_m);
  for (std::size_t m = 0; m < maps.size(); ++m) {
    std::printf("  %s: %d sectors, %d with a label another sector shares\n", maps[m].name.c_str(),
                report.sectors_per_map[m], report.ambiguous_sectors_per_map[m]);
  }
}

/// One table row per estimator, under the column header, and the footnote.
void print_table_rows(const SectorEvalOptions& options, const SectorEvalReport& report) {
  std::printf("%-20s %8s %9s %12s %13s %17s %9s %22s %6s %14s\n", "estimator", "success",
              "sector id", "mean pos err", "mean head err", "median err (ok)", "median",
              "localized/ambig./not", "false", "ambiguity det.");
  for (const SectorEvalResult& r : report.results) {
    char verdicts[48], median_err[48];
    std::snprintf(verdicts, sizeof verdicts, "%d/%d/%d", r.localized, r.ambiguous, r.not_localized);
    std::snprintf(median_err, sizeof median_err, "%.3f m %.2f deg", r.median_position_error_m,
                  r.median_heading_error_deg);
    std::printf("%-20s %7.1f%% %9s %10.3f m %9.2f deg %17s %6.2f ms %22s %6d %14s\n",
                to_string(r.estimator).c_str(), 100.0 * r.success_rate,
                percent_or_dash(r.sector_identification_rate).c_str(), r.mean_position_error_m,
                r.mean_heading_error_deg, median_err, r.median_ms, verdicts, r.false_fixes,
                percent_or_dash(r.ambiguity_detection_rate).c_str());
  }
  std::printf(
      "success: <= %.2f m and <= %.1f deg, not 'not localized'; sector id: the estimate names "
      "the true sector; false: failures reported as localized; ambiguity det.: in sectors whose "
      "label is shared or periodic, 'ambiguous' answers over those plus wrong 'localized' "
      "ones.\n",
      options.success_xy, options.success_theta * 180.0 / 3.14159265358979);
}

}  // namespace

void run_sector_eval(const SectorEvalArgs& args) {
  std::vector<SectorEvalMap> maps;
  for (const auto& path : args.maps)
    maps.push_back({path, load_polygon_map(map_input_path(path, "--maps"), limits())});
  const SectorEvalOptions& options = args.options;
  const std::string what = "poses (" + std::to_string(maps.size()) + " polygon maps x " +
                           std::to_string(options.trials) + " trials, " +
                           std::to_string(options.estimators.size()) + " estimators)";
  const SectorEvalReport report =
      run_sector_evaluation(maps, options, progress_line("eval", what, args.quiet));
  if (!args.trials_out.empty()) write_trials(args.trials_out, report, options);
  if (args.json) return print_json(maps, options, report);
  print_table_title(maps, options, report);
  print_table_rows(options, report);
}

}  // namespace gridloc::cli
