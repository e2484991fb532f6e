#include "disambiguate_simulated.hpp"

#include <cstdio>

#include "disambiguate_grid.hpp"
#include "gridloc/engine/evaluation/engine_loop.hpp"
#include "options.hpp"

namespace gridloc::cli {
namespace {

/// The sensor: a laser for --scan or --sensor laser, else the sonar ring.
EngineLoopOptions loop_options(const DisambiguateArgs& args) {
  EngineLoopOptions options;
  options.planner = planner_options(args);
  options.laser.enabled = !args.scan.empty() || (args.readings.empty() && args.sensor == "laser");
  options.laser.max_range = args.max_range;
  return options;
}

}  // namespace

nlohmann::json simulated_run_on_grid(const OccupancyMap& map, const SonarRing& ring,
                                     const DisambiguateArgs& args) {
  const EngineLoop loop(map, ring, loop_options(args));
  const Pose2 truth = parse_pose(args.pose, "--pose");
  std::vector<Pose2> hypotheses = loop.hypotheses(loop.observe(truth, args.seed));
  const EngineLoopRun run = loop.run(truth, std::move(hypotheses), args.seed);
  nlohmann::json out = plan_json(run.plan, run.true_hypothesis);
  out["noise_free_path_length_m"] = run.noise_free.path_length;
  out["noise_free_resolved"] = run.noise_free.resolved;
  if (args.json) return out;
  print_grid_hypotheses(run.hypotheses);
  std::printf("%s after %zu stops, path %.3f m (noise-free plan: %.3f m); the truth %s\n",
              run.plan.resolved ? "resolved" : run.plan.ended.c_str(), run.plan.stops.size(),
              run.plan.path_length, run.noise_free.path_length,
              out["true_hypothesis_survived"] == true ? "stands" : "was lost");
  return out;
}

GridDisambiguationSimulation engine_loop_simulation() {
  return {simulated_run_on_grid};
}

}  // namespace gridloc::cli
