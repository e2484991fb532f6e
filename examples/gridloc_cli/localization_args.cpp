#include "localization_args.hpp"

#include <chrono>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/echo_filter.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/readings_io.hpp"

namespace gridloc::cli {

void LocalizationArgs::add_to(CLI::App* cmd, const std::string& global_help) {
  if (ring.empty()) ring = data_dir() + "/sensors/wheelchair_14.yaml";
  cmd->add_option("--map", map, "map_server YAML (or OctoMap .bt/.ot) of the known map")
      ->required();
  octomap.add_to(cmd);
  cmd->add_option("--ring", ring, "sonar ring YAML")->capture_default_str();
  cmd->add_option("--readings", readings, "sonar readings JSON {\"ranges_m\": [...]}");
  cmd->add_option("--scan", scan, "laser/IR scan CSV: angle_rad,range_m per line");
  cmd->add_option("--max-range", max_range, "scan max range (m); longer ranges are no return")
      ->capture_default_str();
  cmd->add_option("--prior", prior, "prior pose x,y,theta (m, m, rad)");
  cmd->add_flag("--global", whole_map, global_help);
  cmd->add_option("--window-xy", window.half_xy, "half width of the search square (m)")
      ->capture_default_str();
  cmd->add_option("--window-theta", window.half_theta, "half width of the heading cone (rad)")
      ->capture_default_str();
  cmd->add_option("--step-xy", window.step_xy, "translation step = grid cell (m)")
      ->capture_default_str();
  cmd->add_option("--step-theta", window.step_theta, "heading step (rad)")->capture_default_str();
  cmd->add_option("--local", local, "local grid: oriented | turned")->capture_default_str();
  cmd->add_option("--global-grid", global, "global grid: thinned | raw")->capture_default_str();
  cmd->add_option("--levels", levels, "multiresolution levels")->capture_default_str();
  search.add_to(cmd);
}

Localization prepare_localization(const LocalizationArgs& a) {
  using clock = std::chrono::steady_clock;
  if (a.whole_map == !a.prior.empty()) throw Error("give either --prior x,y,theta or --global");
  if (a.readings.empty() == a.scan.empty()) {
    throw Error("give either --readings (sonar ring) or --scan (laser/IR scan CSV)");
  }
  Localization l;
  std::vector<std::vector<double>> firings;
  if (a.scan.empty()) {
    firings = load_firings(a.readings);
    l.firings = static_cast<int>(firings.size());
    l.observation.ranges = firings.front();
  } else {
    l.observation.scan = load_scan_csv(a.scan, a.max_range);
  }
  const auto t0 = clock::now();
  CorrelationOptions o;
  o.local = parse_local(a.local);
  o.global = parse_global(a.global);
  a.search.apply(o);
  o.resolution = a.window.step_xy;
  o.levels = a.levels;
  // A scan needs no ring: the padding covers its max range instead.
  o.reach_m = l.observation.scan ? a.max_range : 0.0;
  OccupancyMap map = load_map(a.map, a.octomap.slice);
  if (l.observation.scan) {
    l.estimator = std::make_unique<CorrelationEstimator>(std::move(map), o);
  } else {
    SonarRing ring = load_sonar_ring(a.ring);
    if (firings.size() > 1) {  // consecutive firings: keep the echoes they repeat
      FilteredReadings f = filter_echoes(ring, firings);
      l.observation.ranges = std::move(f.ranges);
      l.observation.rejected = std::move(f.rejected);
    }
    l.estimator = std::make_unique<CorrelationEstimator>(std::move(map), std::move(ring), o);
  }
  l.precompute_ms = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  l.window = a.window;
  if (a.whole_map) {
    l.window = l.estimator->global_window(l.observation);
  } else {
    l.window.center = parse_pose(a.prior, "--prior");
  }
  return l;
}

}  // namespace gridloc::cli
