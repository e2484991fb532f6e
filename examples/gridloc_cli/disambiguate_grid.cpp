#include "disambiguate_grid.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "disambiguate_simulated.hpp"
#include "gridloc/engine/disambiguation/disambiguation_planner.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/readings_io.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

/// The sensor: a laser for --scan, else the sonar ring.
DisambiguationPlannerOptions first_stop_options(const DisambiguateArgs& args) {
  DisambiguationPlannerOptions options;
  options.planner = planner_options(args);
  options.laser = !args.scan.empty();
  options.laser_range_m = args.max_range;
  return options;
}

void check_inputs(const DisambiguateArgs& args) {
  if (args.pose.empty() && args.scan.empty() && args.readings.empty()) {
    throw Error(
        "disambiguate: give the start with --pose x,y,theta, --readings R.json or "
        "--scan S.csv");
  }
  if (args.rotation) throw Error("--rotation belongs to polygon maps (the engine finds headings)");
  if (std::isfinite(args.range)) {
    throw Error(
        "--range belongs to polygon maps; on an occupancy map the sensor's own range "
        "counts (--max-range for a laser, the ring's for sonars)");
  }
}

/// The observation taken at the start, from the file given.
Observation sensed_at_start(const DisambiguateArgs& args) {
  Observation observation;
  if (!args.scan.empty()) {
    observation.scan = load_scan_csv(input_path(args.scan, "--scan"), args.max_range, limits());
  } else {
    observation.ranges = load_readings(input_path(args.readings, "--readings"), limits());
  }
  return observation;
}

/// --readings or --scan: the hypotheses and the first stop (nothing sensed there yet).
nlohmann::json first_stop(const OccupancyMap& map, const SonarRing& ring,
                          const DisambiguateArgs& args) {
  const DisambiguationPlanner planner(map, ring, first_stop_options(args));
  const std::vector<Pose2> hypotheses = planner.hypotheses(sensed_at_start(args));
  const MinimumDistancePlan plan = planner.next_stop(hypotheses, args.seed);
  nlohmann::json out = plan_json(plan, -1);
  out["ended"] = plan.stops.empty() ? plan.ended : "drive to the stop, sense, and ask again";
  if (args.json) return out;
  print_grid_hypotheses(hypotheses);
  if (plan.stops.empty()) {
    std::printf("%s: no stop to drive to\n", plan.resolved ? "unique" : plan.ended.c_str());
  } else {
    const LocalizationStop& stop = plan.stops.front();
    std::printf(
        "drive %.3f m to (%.3f, %.3f) in the start frame and sense there (expected to "
        "rule out %.2f hypotheses)\n",
        stop.route_length, stop.point.x(), stop.point.y(), stop.info);
  }
  return out;
}

}  // namespace

void print_grid_hypotheses(const std::vector<Pose2>& hypotheses) {
  std::printf("%zu hypotheses from the engine's global search\n", hypotheses.size());
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const Pose2& h = hypotheses[i];
    std::printf("  %2zu  (%.3f, %.3f, %.3f rad)\n", i, h.x, h.y, h.theta);
  }
}

void run_disambiguate_on_grid(const DisambiguateArgs& args,
                              const GridDisambiguationSimulation& simulation) {
  check_inputs(args);
  make_out_dir(args.out);
  const SonarRing ring =
      load_sonar_ring(args.ring.empty() ? data_dir() + "/sensors/wheelchair_14.yaml"
                                        : input_path(args.ring, "--ring"),
                      limits());
  const OccupancyMap map = load_map(args.map);
  const nlohmann::json out =
      args.pose.empty() ? first_stop(map, ring, args) : simulation.run(map, ring, args);
  if (args.json) std::cout << out.dump(2) << "\n";
  if (!args.out.empty()) {
    write_plan_json(args.out, out);
    if (!args.json) std::printf("wrote %s/disambiguation.json\n", args.out.c_str());
  }
}

}  // namespace gridloc::cli
