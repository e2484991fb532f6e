// What `gridloc eval` writes for seed 001's protocol: every trial as CSV (--trials-out), the
// report as JSON (--json) or as the table.
#include "eval_output.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "calibration_render.hpp"
#include "commands.hpp"
#include "gridloc/engine/evaluation/calibration.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc::cli {
namespace {

/// `v` times `scale` as a table cell: "-" for NaN, a percentage when `scale` > 1.
std::string percent_or_dash(double v, double scale) {
  char buf[32];
  if (std::isnan(v)) return std::string("-");
  std::snprintf(buf, sizeof buf, "%.*f", scale > 1.0 ? 1 : 3, v * scale);
  return std::string(buf) + (scale > 1.0 ? "%" : "");
}

/// `v` with one decimal as a table cell: "-" for NaN.
std::string decimal_or_dash(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

/// A configuration's name in the table and the plot's legend.
std::string configuration_name(const EvalConfiguration& c) {
  if (c.estimator == EstimatorKind::Icp) return to_string(c.estimator);
  return to_string(c.estimator) + ", " + to_string(c.local) + " + " + to_string(c.global);
}

}  // namespace

void write_calibration(const std::string& path, const EvalReport& report,
                       const std::string& title) {
  const std::vector<double> levels = coverage_levels();
  std::vector<CoverageCurve> curves;
  for (std::size_t c = 0; c < report.configurations.size(); ++c) {
    std::vector<CalibrationSample> samples;
    for (const TrialRecord& record : report.records) {
      if (record.configuration != c) continue;
      const Estimate& e = record.estimate;
      samples.push_back({e.pose, e.covariance, record.truth, e.verdict == Verdict::Localized});
    }
    const ConfigurationResult& result = report.configurations[c];
    curves.push_back({configuration_name(result.configuration) + " (" +
                          std::to_string(result.calibration.localized) + " localized)",
                      position_coverage(samples, levels)});
  }
  write_calibration_plot(path, "Calibration: position errors within the covariance's p ellipse",
                         title, levels, curves);
}

void write_trials(const std::string& path, const EvalReport& report, const EvalOptions& options) {
  std::ofstream out(path);
  if (!out) throw Error("--trials-out: cannot write " + path);
  out << "map,trial,local,global,success,wrong_prior,furniture,position_error_m,"
         "heading_error_deg,score,normalized_score,second_score,confidence,std_x,std_y,"
         "std_theta,on_window_edge,agreement,rejected_sonars,estimator,rises_past_window_edge,"
         "verdict\n";
  for (const TrialRecord& r : report.records) {
    const EvalConfiguration& c = options.configurations[r.configuration];
    const Estimate& e = r.estimate;
    out << r.map << ',' << r.trial << ',' << to_string(c.local) << ',' << to_string(c.global) << ','
        << r.success << ',' << r.wrong_prior << ',' << r.furniture << ',' << r.position_error_m
        << ',' << r.heading_error_deg << ',' << e.score << ',' << e.normalized_score << ','
        << e.second_score << ',' << e.confidence << ',' << std::sqrt(e.covariance(0, 0)) << ','
        << std::sqrt(e.covariance(1, 1)) << ',' << std::sqrt(e.covariance(2, 2)) << ','
        << e.on_window_edge << ',' << e.agreement << ',' << r.rejected_sonars << ','
        << to_string(c.estimator) << ',' << e.rises_past_window_edge << ',' << to_string(e.verdict)
        << '\n';
  }
  if (!out) throw Error("--trials-out: writing " + path + " failed");
}

double mean_rejected_sonars(const EvalReport& report) {
  double rejected = 0.0;
  for (const TrialRecord& r : report.records) {
    if (r.configuration == 0) rejected += r.rejected_sonars;
  }
  rejected /= report.trials;
  return rejected;
}

void print_json(const EvalArgs& args, const std::vector<EvalMap>& maps, const EvalReport& report,
                double rejected_per_trial) {
  nlohmann::json configs = nlohmann::json::array();
  for (const auto& c : report.configurations) {
    configs.push_back(
        {{"estimator", to_string(c.configuration.estimator)},
         {"local", to_string(c.configuration.local)},
         {"global", to_string(c.configuration.global)},
         {"success_rate", c.success_rate},
         {"successes", c.successes},
         {"mean_position_error_m", c.mean_position_error_m},
         {"mean_heading_error_deg", c.mean_heading_error_deg},
         {"median_ms", c.median_ms},
         {"sector_identification_rate", nullptr},  // the sector protocol's
         {"auroc", number_or_null(c.auroc)},
         {"failures_flagged_at_95_recall", number_or_null(c.failures_flagged_at_95_recall)},
         {"localized", c.calibration.localized},
         {"nees_mean", number_or_null(c.calibration.nees_mean)},
         {"coverage_2sigma", number_or_null(c.calibration.coverage_2sigma)},
         {"gross_localized", c.calibration.gross_localized}});
  }
  nlohmann::json names = nlohmann::json::array();
  for (const auto& m : maps) names.push_back(m.name);
  std::cout << nlohmann::json{{"trials", report.trials},
                              {"maps", names},
                              {"seed", args.seed},
                              {"strategy", args.search.strategy},
                              // The sonar noise; the laser's is laser_noise_m.
                              {"noise", args.noisy ? "noisy" : args.noise},
                              {"laser_noise_m", args.laser.enabled
                                                    ? nlohmann::json(args.laser.sigma_m)
                                                    : nlohmann::json(nullptr)},
                              {"noisy", args.noisy},
                              {"sensor", args.laser.enabled ? "laser" : "sonar"},
                              {"echo_filter", args.echo_filter},
                              {"echo_filter_rejected_per_trial", rejected_per_trial},
                              {"arc_rule", args.search.arc_rule},
                              {"arc_depth_cells", args.search.arc_depth},
                              {"configurations", configs}}
                   .dump(2)
            << "\n";
}

void print_table_title(const EvalArgs& args, const EvalOptions& options, const SonarRing& ring,
                       std::size_t maps, const EvalReport& report, double rejected_per_trial) {
  char filter[96] = "echo filter off";
  if (args.echo_filter) {
    std::snprintf(filter, sizeof filter, "echo filter on (%d firings, %.2f of %zu sonars rejected)",
                  options.echo_firings, rejected_per_trial, ring.sonars.size());
  }
  std::printf(
      "seed 001 protocol%s: %d trials (%zu maps), seed %llu, %s search, %s noise, %s arcs of "
      "depth %.2g cells, %s\n",
      args.noisy ? " (noisy: harsh noise, wrong priors, furniture)" : "", report.trials, maps,
      static_cast<unsigned long long>(args.seed), args.search.strategy.c_str(),
      args.noisy ? "harsh" : args.noise.c_str(), args.search.arc_rule.c_str(),
      args.search.arc_depth, filter);
  if (args.laser.enabled) {
    std::printf("laser: %d beams, %.1f m max range, %.3f m noise\n", args.laser.beams,
                args.laser.max_range, args.laser.sigma_m);
  }
}

void print_table_rows(const EvalReport& report) {
  std::printf("%-15s %-9s %-8s %9s %14s %16s %10s %7s %9s %9s %7s %6s\n", "estimator", "local",
              "global", "success", "mean pos err", "mean head err", "median", "AUROC", "flagged",
              "2σ cover", "NEES", "gross");
  for (const auto& c : report.configurations) {
    const bool models = c.configuration.estimator != EstimatorKind::Icp;
    std::printf("%-15s %-9s %-8s %8.1f%% %12.3f m %12.2f deg %7.2f ms %7s %9s %9s %7s %6d\n",
                to_string(c.configuration.estimator).c_str(),
                models ? to_string(c.configuration.local).c_str() : "-",
                models ? to_string(c.configuration.global).c_str() : "-", 100.0 * c.success_rate,
                c.mean_position_error_m, c.mean_heading_error_deg, c.median_ms,
                percent_or_dash(c.auroc, 1.0).c_str(),
                percent_or_dash(c.failures_flagged_at_95_recall, 100.0).c_str(),
                percent_or_dash(c.calibration.coverage_2sigma, 100.0).c_str(),
                decimal_or_dash(c.calibration.nees_mean).c_str(), c.calibration.gross_localized);
  }
  std::printf(
      "AUROC: how well the confidence separates successes from failures; flagged: failures "
      "below the confidence that keeps 95%% of successes; over the `localized` answers, 2σ "
      "cover: position errors within the 2-sigma radius (about 86%% when calibrated), NEES: "
      "the mean normalized error squared of (x, y, theta) (3 when calibrated), gross: more "
      "than 0.3 m or 15 deg off.\n");
}

}  // namespace gridloc::cli
