// gridloc heatmap (issue 4): the score volume of a localization as tuning images and files:
// score over x, y (best heading, max over headings), score against heading, the local grid
// on the global grid at the estimate, the raw volume as .npy with its axes in volume.json
// (heatmap_volume.cpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/readings_io.hpp"
#include "gridloc/sensors/sonar_model.hpp"
#include "heatmap_render.hpp"
#include "heatmap_volume.hpp"
#include "localization_args.hpp"
#include "options.hpp"
#include "output_files.hpp"
#include "plot.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

/// Poses a volume may hold: 4 bytes each on disk, ~40 in memory while it is scored.
constexpr long long kMaxPoses = 30'000'000;

struct HeatmapArgs {
  LocalizationArgs inputs;
  std::string truth, out;
  bool step_theta_given = false;  // --step-theta on the command line: honoured by --global too
};

/// Two lines under each image's title: what was matched, and where.
std::string caption(const LocalizationArgs& args, const Observation& observation,
                    const SearchWindow& window, const ScoreVolume& volume,
                    const Estimate& estimate) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text << fs::path(args.map).filename().string() << ", ";
  if (observation.scan) {
    text << "scan of " << observation.scan->ranges.size() << " beams (" << args.search.scan_model
         << " model, " << args.global << " global grid)\n";
  } else {
    text << observation.ranges.size() << " sonar readings (" << args.local << " local grid, "
         << args.global << " global grid, " << args.search.arc_rule << " arcs)\n";
  }
  if (args.whole_map) {
    text << "whole map, every heading";
  } else {
    text << std::setprecision(2) << "window +-" << window.half_xy << " m, +-"
         << std::setprecision(0) << rad2deg(window.half_theta) << " deg around the prior ("
         << std::setprecision(2) << window.center.x << ", " << window.center.y << " m, "
         << std::setprecision(1) << rad2deg(window.center.theta) << " deg)";
  }
  text << std::setprecision(2) << "; lattice " << volume.resolution << " m x "
       << std::setprecision(1) << rad2deg(volume.step_theta) << " deg; best S "
       << std::setprecision(2) << estimate.score << " of "
       << volume.mass[static_cast<std::size_t>(volume.best.it)] << " possible";
  return text.str();
}

/// Refuses a huge volume before allocating it (the estimator's own lattice, clipped to the
/// map): gridloc::Error with the count and what to change.
void check_volume_size(const CorrelationEstimator& estimator, const Observation& observation,
                       const SearchWindow& window) {
  const Lattice lattice = estimator.lattice(observation, window);
  const long long nx = lattice.x1 - lattice.x0 + 1, ny = lattice.y1 - lattice.y0 + 1;
  const double poses = static_cast<double>(nx) * static_cast<double>(ny) * lattice.headings;
  if (poses > static_cast<double>(kMaxPoses)) {
    std::ostringstream message;
    message << "heatmap: the score volume would hold " << nx << " x " << ny << " cells x "
            << lattice.headings << " headings = " << std::llround(poses) << " poses, more than "
            << kMaxPoses
            << "; use a smaller --window-xy or --window-theta, or a larger --step-theta";
    throw Error(message.str());
  }
}

/// The local grid at the refined pose and the map cell of its robot cell.
struct LocalAtEstimate {
  SparseLocalGrid grid;
  Cell robot;
};

/// The local grid at the refined pose: its robot cell and the centre's offset in it.
LocalAtEstimate local_at_estimate(const CorrelationEstimator& estimator,
                                  const Observation& observation, const ScoreVolume& volume,
                                  const Pose2& estimate) {
  const CorrelationOptions& options = estimator.options();
  const Pose2 p = volume.geometry.to_grid_frame(estimate);
  const double res = volume.resolution;
  const Cell robot = volume.geometry.cell_of(p.x, p.y);
  const Eigen::Vector2d centre(p.x - (robot.ix + 0.5) * res, p.y - (robot.iy + 0.5) * res);
  return {observation.scan ? rasterize_scan(*observation.scan, p.theta, res, centre, options.scan)
                           : rasterize(estimator.ring(), observation.ranges, p.theta, res,
                                       options.local, centre, options.sonar, observation.rejected),
          robot};
}

/// The files of a heatmap by key, relative to its folder (volume.json names them so).
nlohmann::json file_names() {
  return {{"score_xy_best_theta", "score_xy_best_theta.png"},
          {"score_xy_max_theta", "score_xy_max_theta.png"},
          {"score_theta", "score_theta.png"},
          {"local_overlay", "local_overlay.png"},
          {"scores", "scores.npy"},
          {"volume", "volume.json"}};
}

/// Writes the four images, scores.npy and volume.json into `dir`.
void write_heatmap_files(const fs::path& dir, const CorrelationEstimator& estimator,
                         const ScoreVolume& volume, const SearchWindow& window,
                         const LocalAtEstimate& local, const HeatmapMarks& marks) {
  auto file = [&](const std::string& name) { return (dir / name).string(); };
  plot::write_png(file("score_xy_best_theta.png"),
                  render_score_xy(volume, estimator.map(), marks, false));
  plot::write_png(file("score_xy_max_theta.png"),
                  render_score_xy(volume, estimator.map(), marks, true));
  plot::write_png(file("score_theta.png"), render_score_theta(volume, marks));
  plot::write_png(file("local_overlay.png"),
                  render_local_overlay(estimator.level(0), volume.geometry, local.grid, local.robot,
                                       estimator.ring().footprint, marks));
  write_npy(file("scores.npy"), volume);
  write_json_file(file("volume.json"), volume_json(volume, window, file_names()),
                  "the volume description");
}

/// The output of `heatmap`: the estimate, its lattice pose, the volume's shape and best
/// score, the files' paths.
nlohmann::json heatmap_json(const Estimate& estimate, const ScoreVolume& volume,
                            const fs::path& dir) {
  const nlohmann::json names = file_names();
  nlohmann::json files;
  for (const auto& [key, name] : names.items()) {
    files[key] = (dir / name.get<std::string>()).string();
  }
  nlohmann::json out = to_json(estimate);
  out["lattice"] = {{"pose", to_json(estimate.lattice_pose)}, {"score", estimate.score}};
  out["volume"] = {{"shape", {volume.headings, volume.ny, volume.nx}},
                   {"max_score", volume.best.score}};
  out["files"] = files;
  return out;
}

void run(const HeatmapArgs& args) {
  if (args.out.empty()) throw Error("--out: give the folder to write the heatmaps in");
  std::optional<Pose2> truth;
  if (!args.truth.empty()) truth = parse_pose(args.truth, "--truth");
  Localization localization = prepare_localization(args.inputs);
  const CorrelationEstimator& estimator = *localization.estimator;
  const Observation& observation = localization.observation;
  SearchWindow& window = localization.window;
  // The volume is exhaustive, so let a coarser heading step make a global one affordable.
  if (args.inputs.whole_map && args.step_theta_given) {
    window.step_theta = args.inputs.window.step_theta;
  }
  check_volume_size(estimator, observation, window);

  const Estimate estimate = estimator.estimate(observation, window);
  const ScoreVolume volume = estimator.score_volume(observation, window);
  const fs::path dir = output_folder(args.out);
  const HeatmapMarks marks{estimate.pose,
                           estimate.alternatives,
                           truth,
                           caption(args.inputs, observation, window, volume, estimate),
                           to_string(estimate.verdict),
                           estimate.confidence,
                           estimate.covariance};
  write_heatmap_files(dir, estimator, volume, window,
                      local_at_estimate(estimator, observation, volume, estimate.pose), marks);

  std::cout << heatmap_json(estimate, volume, dir).dump(2) << "\n";
}

}  // namespace

void add_heatmap(CLI::App& app) {
  auto args = std::make_shared<HeatmapArgs>();
  auto* cmd = app.add_subcommand(
      "heatmap", "Score volume of a localization as images (PNG) and a NumPy file, for tuning");
  cmd->add_option("--out", args->out, "folder for the images and files (created if missing)")
      ->required();
  cmd->add_option("--truth", args->truth, "true pose x,y,theta (m, m, rad), drawn when given");
  args->inputs.add_to(cmd,
                      "no prior: the whole map and every heading (at --step-theta when given)");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--ring"}, {"--readings"}, {"--scan"}});
  cmd->callback([args, cmd] {
    args->step_theta_given = cmd->count("--step-theta") > 0;
    run(*args);
  });
}

}  // namespace gridloc::cli
