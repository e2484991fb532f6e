// gridloc heatmap (issue 4): the score volume of a localization as tuning images and files:
// score over x, y (best heading, max over headings), score against heading, the local grid
// on the global grid at the estimate, the raw volume as .npy with its axes in volume.json.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
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
#include "heatmap_plot.hpp"
#include "heatmap_render.hpp"
#include "localization_args.hpp"
#include "options.hpp"

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

/// NumPy .npy v1.0: magic, version, header length, a Python dict padded with spaces to a
/// multiple of 64 bytes ending in '\n', then little-endian float32 in C order.
void write_npy(const std::string& path, const ScoreVolume& v) {
  static_assert(std::endian::native == std::endian::little, "write_npy assumes little endian");
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(v.headings) + ", " + std::to_string(v.ny) + ", " +
                       std::to_string(v.nx) + "), }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header += std::string((64 - unpadded % 64) % 64, ' ') + "\n";
  std::ofstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot write the score volume");
  const std::uint16_t length = static_cast<std::uint16_t>(header.size());
  f.write("\x93NUMPY\x01\x00", 8);
  f.put(static_cast<char>(length & 0xff));
  f.put(static_cast<char>(length >> 8));
  f << header;
  std::vector<float> data(v.scores.begin(), v.scores.end());
  f.write(reinterpret_cast<const char*>(data.data()),
          static_cast<std::streamsize>(data.size() * sizeof(float)));
  if (!f) throw Error(path + ": cannot write the score volume");
}

nlohmann::json volume_json(const ScoreVolume& v, const SearchWindow& window,
                           const nlohmann::json& files) {
  const GridGeometry& g = v.geometry;
  const Pose2 first = v.pose(0, 0, 0);
  std::vector<double> mass(v.mass.begin(), v.mass.end());
  return {{"file", "scores.npy"},
          {"dtype", "float32, little endian"},
          {"shape", {v.headings, v.ny, v.nx}},
          {"axes", {"heading", "y", "x"}},
          {"index",
           "scores[t, y, x]: heading theta0 + t * step_theta, cell centre (x0, y0) + x * "
           "resolution * x_axis + y * resolution * y_axis (y grows northwards)"},
          {"nx", v.nx},
          {"ny", v.ny},
          {"headings", v.headings},
          {"resolution", v.resolution},
          {"x0", first.x},
          {"y0", first.y},
          {"x_axis", {std::cos(g.yaw), std::sin(g.yaw)}},
          {"y_axis", {-std::sin(g.yaw), std::cos(g.yaw)}},
          {"theta0", v.theta0 + g.yaw},
          {"step_theta", v.step_theta},
          {"theta0_deg", rad2deg(v.theta0 + g.yaw)},
          {"step_theta_deg", rad2deg(v.step_theta)},
          {"map_cell0", {v.ix0, v.iy0}},
          {"map_grid",
           {{"resolution", g.resolution},
            {"origin", {g.origin.x(), g.origin.y()}},
            {"yaw", g.yaw},
            {"width", g.width},
            {"height", g.height}}},
          {"best",
           {{"x", v.best.ix},
            {"y", v.best.iy},
            {"t", v.best.it},
            {"score", v.best.score},
            {"pose", to_json(v.pose(v.best.ix, v.best.iy, v.best.it))}}},
          {"mass", mass},
          {"window",
           {{"center", to_json(window.center)},
            {"half_xy", window.half_xy},
            {"half_theta", window.half_theta},
            {"step_xy", window.step_xy},
            {"step_theta", window.step_theta}}},
          {"files", files}};
}

/// Two lines under each image's title: what was matched, and where.
std::string caption(const LocalizationArgs& a, const Observation& obs, const SearchWindow& w,
                    const ScoreVolume& v, const Estimate& e) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s << fs::path(a.map).filename().string() << ", ";
  if (obs.scan) {
    s << "scan of " << obs.scan->ranges.size() << " beams (" << a.search.scan_model << " model, "
      << a.global << " global grid)\n";
  } else {
    s << obs.ranges.size() << " sonar readings (" << a.local << " local grid, " << a.global
      << " global grid, " << a.search.arc_rule << " arcs)\n";
  }
  if (a.whole_map) {
    s << "whole map, every heading";
  } else {
    s << std::setprecision(2) << "window +-" << w.half_xy << " m, +-" << std::setprecision(0)
      << rad2deg(w.half_theta) << " deg around the prior (" << std::setprecision(2) << w.center.x
      << ", " << w.center.y << " m, " << std::setprecision(1) << rad2deg(w.center.theta) << " deg)";
  }
  s << std::setprecision(2) << "; lattice " << v.resolution << " m x " << std::setprecision(1)
    << rad2deg(v.step_theta) << " deg; best S " << std::setprecision(2) << e.score << " of "
    << v.mass[static_cast<std::size_t>(v.best.it)] << " possible";
  return s.str();
}

void run(const HeatmapArgs& a) {
  if (a.out.empty()) throw Error("--out: give the folder to write the heatmaps in");
  std::optional<Pose2> truth;
  if (!a.truth.empty()) truth = parse_pose(a.truth, "--truth");
  Localization l = prepare_localization(a.inputs);
  const CorrelationEstimator& estimator = *l.estimator;
  const Observation& obs = l.observation;
  const CorrelationOptions& o = estimator.options();
  SearchWindow& window = l.window;
  // The volume is exhaustive, so let a coarser heading step make a global one affordable.
  if (a.inputs.whole_map && a.step_theta_given) window.step_theta = a.inputs.window.step_theta;
  // Refuse a huge volume before allocating it (the estimator's own lattice, clipped to the map).
  const Lattice lattice = estimator.lattice(obs, window);
  const long long nx = lattice.x1 - lattice.x0 + 1, ny = lattice.y1 - lattice.y0 + 1;
  const double poses = static_cast<double>(nx) * static_cast<double>(ny) * lattice.headings;
  if (poses > static_cast<double>(kMaxPoses)) {
    std::ostringstream m;
    m << "heatmap: the score volume would hold " << nx << " x " << ny << " cells x "
      << lattice.headings << " headings = " << std::llround(poses) << " poses, more than "
      << kMaxPoses << "; use a smaller --window-xy or --window-theta, or a larger --step-theta";
    throw Error(m.str());
  }

  const Estimate e = estimator.estimate(obs, window);
  const ScoreVolume v = estimator.score_volume(obs, window);

  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (!fs::is_directory(a.out)) throw Error("--out " + a.out + ": cannot create the folder");
  const fs::path dir(a.out);
  auto file = [&](const std::string& name) { return (dir / name).string(); };

  HeatmapMarks marks;
  marks.estimate = e.pose;
  marks.hypotheses = e.alternatives;
  marks.truth = truth;
  marks.caption = caption(a.inputs, obs, window, v, e);

  // The local grid at the refined pose: its robot cell and the centre's offset in it.
  const Pose2 p = v.geometry.to_grid_frame(e.pose);
  const double res = v.resolution;
  const Cell robot = v.geometry.cell_of(p.x, p.y);
  const Eigen::Vector2d centre(p.x - (robot.ix + 0.5) * res, p.y - (robot.iy + 0.5) * res);
  const SparseLocalGrid local = obs.scan ? rasterize_scan(*obs.scan, p.theta, res, centre, o.scan)
                                         : rasterize(estimator.ring(), obs.ranges, p.theta, res,
                                                     o.local, centre, o.sonar, obs.rejected);

  // volume.json names the files relative to its folder; stdout gives their paths.
  const nlohmann::json names = {{"score_xy_best_theta", "score_xy_best_theta.png"},
                                {"score_xy_max_theta", "score_xy_max_theta.png"},
                                {"score_theta", "score_theta.png"},
                                {"local_overlay", "local_overlay.png"},
                                {"scores", "scores.npy"},
                                {"volume", "volume.json"}};
  nlohmann::json files;
  for (const auto& [key, name] : names.items()) files[key] = file(name.get<std::string>());
  plot::write_png(file("score_xy_best_theta.png"),
                  render_score_xy(v, estimator.map(), marks, false));
  plot::write_png(file("score_xy_max_theta.png"), render_score_xy(v, estimator.map(), marks, true));
  plot::write_png(file("score_theta.png"), render_score_theta(v, marks));
  plot::write_png(file("local_overlay.png"),
                  render_local_overlay(estimator.level(0), v.geometry, local, robot,
                                       estimator.ring().footprint, marks));
  write_npy(file("scores.npy"), v);
  {
    std::ofstream f(file("volume.json"));
    f << volume_json(v, window, names).dump(2) << "\n";
    if (!f) throw Error(file("volume.json") + ": cannot write the volume description");
  }

  nlohmann::json j = to_json(e);
  j["lattice"] = {{"pose", to_json(e.lattice_pose)}, {"score", e.score}};
  j["volume"] = {{"shape", {v.headings, v.ny, v.nx}}, {"max_score", v.best.score}};
  j["files"] = files;
  std::cout << j.dump(2) << "\n";
}

}  // namespace

void add_heatmap(CLI::App& app) {
  auto a = std::make_shared<HeatmapArgs>();
  auto* cmd = app.add_subcommand(
      "heatmap", "Score volume of a localization as images (PNG) and a NumPy file, for tuning");
  cmd->add_option("--out", a->out, "folder for the images and files (created if missing)")
      ->required();
  cmd->add_option("--truth", a->truth, "true pose x,y,theta (m, m, rad), drawn when given");
  a->inputs.add_to(cmd, "no prior: the whole map and every heading (at --step-theta when given)");
  cmd->callback([a, cmd] {
    a->step_theta_given = cmd->count("--step-theta") > 0;
    run(*a);
  });
}

}  // namespace gridloc::cli
