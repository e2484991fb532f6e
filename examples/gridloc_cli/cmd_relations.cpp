// gridloc relations: scan matching on a real log, scored against the SLAM benchmark's
// ground-truth relations (issue 5).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>

#include "commands.hpp"
#include "gridloc/engine/evaluation/relations.hpp"
#include "gridloc/engine/icp/robust_icp.hpp"
#include "gridloc/grids/error.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "plot.hpp"
#include "relations_render.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

struct RelationsArgs {
  std::string log, relations, estimator = "icp", trials_out, plot;
  int plot_pairs = 6;
  double time_offset = 0.0;
  double tolerance = 0.002;
  RelationEvalOptions options;
  SearchArgs search = [] {
    SearchArgs s;
    // RelationEvalOptions' default (exhaustive_search())
    const CorrelationOptions defaults = exhaustive_search();
    s.strategy = "exhaustive";
    s.covariance_cells = defaults.covariance_cells;
    s.covariance_temperature = defaults.covariance_temperature;
    s.covariance_peaks = defaults.covariance_spans_peaks;
    return s;
  }();
  bool json = false;
};

constexpr const char* kTrialsHeader =
    "pair,t1,t2,motion_m,motion_deg,returns,translation_error_m,rotation_error_deg,ms,converged,"
    "failed,verdict,confidence,refined,search_cells,overlap,sigma_major_m,sigma_minor_m,"
    "sigma_theta_deg,within_2sigma,answer_overlap";

/// One trial as a CSV row of kTrialsHeader (verdict and confidence empty for icp).
std::string trial_row(const RelationTrial& t) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu,%.6f,%.6f,%.4f,%.3f,%d,%.6f,%.4f,%.3f,%d,%d,", t.pair, t.t1,
                t.t2, t.motion_m, t.motion_deg, t.returns, t.translation_error_m,
                t.rotation_error_deg, t.ms, t.converged ? 1 : 0, t.failed ? 1 : 0);
  std::string row = buf;
  if (t.verdict) row += to_string(*t.verdict);
  row += ',';
  if (!std::isnan(t.confidence)) {
    std::snprintf(buf, sizeof buf, "%.4f", t.confidence);
    row += buf;
  }
  std::snprintf(buf, sizeof buf, ",%d,%zu,%.4f", t.refined ? 1 : 0, t.search_cells, t.overlap);
  row += buf;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(t.covariance.topLeftCorner<2, 2>());
  const auto sigma = [](double variance) { return std::sqrt(std::max(0.0, variance)); };
  std::snprintf(buf, sizeof buf, ",%.4f,%.4f,%.4f,%d,%.4f", sigma(axes.eigenvalues()(1)),
                sigma(axes.eigenvalues()(0)), sigma(t.covariance(2, 2)) * 180.0 / std::numbers::pi,
                t.within_2sigma ? 1 : 0, t.answer_overlap);
  return row + buf;
}

/// The trials as CSV into `out`, opened on `path` before the run (so a bad path fails first).
void write_trials(std::ofstream& out, const std::string& path, const RelationEvalReport& report) {
  out << kTrialsHeader << '\n';
  for (const RelationTrial& t : report.trials) out << trial_row(t) << '\n';
  out.flush();
  if (!out) throw Error("--trials-out: writing " + path + " failed");
}

/// A number, or null when it is not finite.
nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// A failure table as JSON rows {key: label, "pairs", "failures"}.
nlohmann::json failure_rows(const std::vector<FailureRow>& rows, const char* key) {
  nlohmann::json out = nlohmann::json::array();
  for (const FailureRow& row : rows)
    out.push_back({{key, row.label}, {"pairs", row.pairs}, {"failures", row.failures}});
  return out;
}

/// A failure table as text lines under `title`.
void print_rows(const char* title, const std::vector<FailureRow>& rows) {
  std::printf("failures by %s:\n", title);
  for (const FailureRow& row : rows) {
    std::printf("  %-14s %5d pairs, %4d failures (%.1f %%)\n", row.label.c_str(), row.pairs,
                row.failures, row.pairs > 0 ? 100.0 * row.failures / row.pairs : 0.0);
  }
}

/// The worst `args.plot_pairs` pairs drawn into args.plot.
void write_plot(const RelationsArgs& args, const CarmenLog& log,
                const std::vector<RelationPair>& pairs, const RelationEvalReport& report) {
  RelationsPicture picture;
  for (std::size_t k : worst_trials(report.trials, static_cast<std::size_t>(args.plot_pairs))) {
    const RelationTrial& t = report.trials[k];
    picture.panels.push_back({scan_returns(log.lasers[pairs[t.pair].first].scan),
                              scan_returns(log.lasers[pairs[t.pair].second].scan), t});
  }
  picture.title = "gridloc relations: the worst " + std::to_string(picture.panels.size()) + " of " +
                  std::to_string(report.pairs) + " pairs (" + args.estimator + ")";
  picture.caption = std::filesystem::path(args.log).filename().string() + ", " +
                    std::to_string(report.failures) + " failures (beyond " +
                    plot::fixed(args.options.failure_xy, 2) + " m or " +
                    plot::fixed(args.options.failure_theta * 180.0 / std::numbers::pi, 0) +
                    " deg); each panel in the reference scan's frame";
  plot::write_png(args.plot, render_relations(picture));
}

void run(const RelationsArgs& args) {
  RelationEvalOptions options = args.options;
  options.matcher = parse_estimator_kind(args.estimator);
  args.search.apply(options.correlation);
  options.correlation.limits = limits();
  validate(options);
  std::ofstream trials;
  if (!args.trials_out.empty()) {
    trials.open(args.trials_out);
    if (!trials) throw Error("--trials-out: cannot write " + args.trials_out);
  }
  require_flag(args.plot_pairs >= 1, "--plot-pairs", args.plot_pairs, "must be at least 1");
  if (!args.plot.empty() && !std::ofstream(args.plot)) {
    throw Error("--plot: cannot write " + args.plot);
  }
  CarmenOptions carmen;
  carmen.limits = limits();
  const CarmenLog log = load_carmen_log(input_path(args.log, "--log"), carmen);
  const auto relations = load_slam_relations(input_path(args.relations, "--relations"), limits());
  const auto pairs = pair_relations(relations, log, args.time_offset, args.tolerance);
  const RelationEvalReport report = evaluate_relations(log, pairs, options);
  if (trials.is_open()) write_trials(trials, args.trials_out, report);
  if (!args.plot.empty()) write_plot(args, log, pairs, report);
  const nlohmann::json out = {
      {"estimator", args.estimator},
      {"relations", relations.size()},
      {"pairs", report.pairs},
      {"translation_error_m",
       {{"mean", report.translation_error_m.mean}, {"std", report.translation_error_m.std}}},
      {"rotation_error_deg",
       {{"mean", report.rotation_error_deg.mean}, {"std", report.rotation_error_deg.std}}},
      {"failures", report.failures},
      {"not_converged", report.not_converged},
      {"median_ms", report.median_ms},
      {"failures_by_overlap", failure_rows(report.failures_by_overlap, "band")},
      {"failures_by_verdict", failure_rows(report.failures_by_verdict, "verdict")},
      {"overlapping",
       {{"min_overlap", options.overlapping_share},
        {"pairs", report.overlapping.pairs},
        {"failures", report.overlapping.failures}}},
      {"calibration",
       {{"answers", report.calibration.localized},
        {"nees_mean", json_number(report.calibration.nees_mean)},
        {"coverage_2sigma", json_number(report.calibration.coverage_2sigma)},
        {"failures_within_2sigma", report.covered_failures}}},
      {"seed", args.options.seed}};
  if (args.json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf(
      "%s on %d relation pairs (of %zu relations): translation error %.4f +- %.4f m, "
      "rotation error %.3f +- %.3f deg, %d failures, %.2f ms per match\n",
      args.estimator.c_str(), report.pairs, relations.size(), report.translation_error_m.mean,
      report.translation_error_m.std, report.rotation_error_deg.mean, report.rotation_error_deg.std,
      report.failures, report.median_ms);
  print_rows("overlap (share of the current scan's returns near the reference's)",
             report.failures_by_overlap);
  print_rows("verdict", report.failures_by_verdict);
  std::printf("%s: %d pairs, %d failures\n", report.overlapping.label.c_str(),
              report.overlapping.pairs, report.overlapping.failures);
  const CalibrationSummary& c = report.calibration;
  std::printf(
      "answers used (localized; icp: converged): %d, NEES %.2f, within the 2-sigma ellipse "
      "%.1f %%, failures within it %d\n",
      c.localized, c.nees_mean, 100.0 * c.coverage_2sigma, report.covered_failures);
}

}  // namespace

void add_relations(CLI::App& app) {
  auto args = std::make_shared<RelationsArgs>();
  auto* cmd = app.add_subcommand(
      "relations", "Match the scan pairs of a CARMEN log named by SLAM benchmark relations");
  cmd->add_option("--log", args->log,
                  "CARMEN log, plain or gzip (FLASER / ROBOTLASER1 lines; - reads standard input)")
      ->required();
  cmd->add_option("--relations", args->relations,
                  "relations file: t1 t2 x y z roll pitch yaw (- reads standard input)")
      ->required();
  cmd->add_option("--estimator", args->estimator,
                  "icp (seed 004's robust ICP) | correlation (the search on the reference "
                  "scan's map) | correlation+icp")
      ->capture_default_str();
  cmd->add_option("--time-offset", args->time_offset,
                  "added to the log's times to reach the relations' (Intel: 976052857.337311)")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance, "time matching tolerance (s)")
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "seed of the prior's noise")->capture_default_str();
  cmd->add_option("--prior-noise-xy", args->options.prior_noise_xy,
                  "uniform noise added to the logged motion's x and y (m)")
      ->capture_default_str();
  cmd->add_option("--prior-noise-theta", args->options.prior_noise_theta,
                  "uniform noise added to the logged motion's heading (rad)")
      ->capture_default_str();
  IcpOptions& icp = args->options.icp;
  cmd->add_option("--icp-gap", icp.gap_m, "ICP segmentation gap (m)")->capture_default_str();
  cmd->add_option("--icp-min-segment", icp.min_segment_points,
                  "ICP: segments with fewer points give no matching points")
      ->capture_default_str();
  cmd->add_flag("!--icp-all-points", icp.use_complexity,
                "ICP: match every point, not N_s = C_f * N_m per segment");
  cmd->add_option("--icp-max-correspondence", icp.max_correspondence_m,
                  "ICP: pairs farther apart are not used (m)")
      ->capture_default_str();
  cmd->add_option("--icp-converged", icp.converged_xy_m,
                  "ICP: stop when an update moves less than this (m; the same in rad turns)")
      // each() runs before the value is stored: parse it here for the heading threshold.
      ->each([&icp](const std::string& value) { icp.converged_theta_rad = std::stod(value); })
      ->capture_default_str();
  cmd->add_option("--icp-breakpoint-angle", icp.breakpoint_angle_rad,
                  "ICP: grazing angle of the range-adaptive gap (rad; 0: fixed gap)")
      ->capture_default_str();
  cmd->add_option("--icp-min-matching-points", icp.min_matching_points,
                  "ICP: at least this many matching points per scan")
      ->capture_default_str();
  cmd->add_option("--icp-tangent-points", icp.tangent_points,
                  "ICP: the reference's tangent is the line through this many points (<= 2: "
                  "the chord to a neighbour)")
      ->capture_default_str();
  cmd->add_option("--icp-max-iterations", icp.max_iterations, "ICP iteration limit")
      ->capture_default_str();
  cmd->add_option("--map-resolution", args->options.map_resolution,
                  "correlation: cell of the reference scan's map = translation step (m)")
      ->capture_default_str();
  cmd->add_flag("!--no-join-returns", args->options.join_returns,
                "correlation: draw the reference scan's returns alone, not joined into walls");
  cmd->add_option("--join-gap", args->options.join_gap_m,
                  "correlation: consecutive returns closer than this plus the range-adaptive "
                  "part are one wall (m)")
      ->capture_default_str();
  cmd->add_option("--join-grazing-angle", args->options.join_grazing_rad,
                  "correlation: the range-adaptive part joins walls seen down to this grazing "
                  "angle (rad; 0: the fixed gap alone)")
      ->capture_default_str();
  cmd->add_option("--window-margin-xy", args->options.window_margin_xy,
                  "correlation: the window covers the prior's noise plus this (m)")
      ->capture_default_str();
  cmd->add_option("--window-margin-theta", args->options.window_margin_theta,
                  "correlation: ... plus this (rad)")
      ->capture_default_str();
  cmd->add_option("--refine-max-shift", args->options.refine_max_shift_m,
                  "correlation+icp: ICP's pose is kept within this of the search's (m)")
      ->capture_default_str();
  cmd->add_option("--refine-max-turn", args->options.refine_max_turn_rad,
                  "correlation+icp: ... and within this turn (rad)")
      ->capture_default_str();
  cmd->add_flag("--icp-from-prior", args->options.icp_from_prior,
                "correlation+icp: ICP from the prior too; the answer fitting more pairs wins");
  args->search.add_to(cmd);
  cmd->add_option("--overlap-radius", args->options.overlap_radius_m,
                  "a return overlaps when it lies within this of the other scan's at the true "
                  "motion (m)")
      ->capture_default_str();
  cmd->add_option("--overlapping", args->options.overlapping_share,
                  "pairs sharing at least this share of returns count as overlapping")
      ->capture_default_str();
  cmd->add_option("--max-search-mb", args->options.max_search_mb,
                  "refuse a pair whose correlation search grids would take more (MB)")
      ->capture_default_str();
  cmd->add_option("--trials-out", args->trials_out,
                  "write each pair's error, time and verdict to this CSV file");
  cmd->add_option("--plot", args->plot,
                  "draw the worst pairs (failures first) into this PNG: the reference scan, the "
                  "current one at the relation and at the answer, the 2-sigma ellipse");
  cmd->add_option("--plot-pairs", args->plot_pairs, "pairs --plot draws")->capture_default_str();
  cmd->add_flag("--json", args->json, "print JSON");
  read_stdin_at_most_once(cmd, {{"--log"}, {"--relations"}});
  cmd->callback([args] { run(*args); });
}

}  // namespace gridloc::cli
