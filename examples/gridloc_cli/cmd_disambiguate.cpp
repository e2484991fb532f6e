// gridloc disambiguate: where to drive, as little as possible, to tell look-alike places apart
// (seed 002's COL and UAL): the hypotheses that match the view at the start, the stops, the
// path in the start frame and in each surviving hypothesis's world frame, the lower bound.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "disambiguate_common.hpp"
#include "disambiguate_grid.hpp"
#include "disambiguate_simulated.hpp"
#include "disambiguation_render.hpp"
#include "gridloc/engine/disambiguation/hypothesis_generation.hpp"
#include "gridloc/engine/disambiguation/minimum_distance.hpp"
#include "gridloc/engine/disambiguation/overlay.hpp"
#include "gridloc/engine/disambiguation/polygon_space.hpp"
#include "gridloc/engine/disambiguation/sampling.hpp"
#include "gridloc/engine/disambiguation/travel_bound.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "limit_options.hpp"
#include "options.hpp"
#include "plot.hpp"
#include "stdin_input.hpp"

namespace gridloc::cli {
namespace {

namespace fs = std::filesystem;

/// A range > 0, inf allowed (CLI::PositiveNumber lets NaN through).
CLI::Validator positive_range() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !(value > 0.0)) {
          return "the range must be a number > 0 (or inf), got " + text;
        }
        return {};
      },
      "RANGE");
}

PolygonSpaceOptions space_options(const DisambiguateArgs& args) {
  PolygonSpaceOptions options;
  options.range = args.range;
  return options;
}

/// The polygon map; it takes a simulated start (--pose), not sensed data.
PolygonMap load_polygon_inputs(const DisambiguateArgs& args) {
  if (!args.scan.empty() || !args.readings.empty()) {
    throw Error(
        "disambiguate: on a polygon map give the start with --pose x,y,theta (its view is "
        "simulated); --scan and --readings go with an occupancy-grid map");
  }
  if (args.pose.empty()) throw Error("disambiguate: give the start with --pose x,y,theta");
  return load_polygon_map(map_input_path(args.map), limits());
}

nlohmann::json polygon_plan_json(const MinimumDistancePlan& plan, int true_index,
                                 const TravelBound& bound) {
  nlohmann::json out = plan_json(plan, true_index);
  out["lower_bound_m"] = number_or_null(bound.distance);
  out["pairwise_lower_bound_m"] = number_or_null(bound.pairwise);
  out["lower_bound_is_optimum"] = bound.optimal;
  return out;
}

void print_summary(const MinimumDistancePlan& plan, const TravelBound& bound) {
  std::printf("%zu hypotheses match the view at the start\n", plan.hypotheses.size());
  for (std::size_t i = 0; i < plan.hypotheses.size(); ++i) {
    const Pose2& h = plan.hypotheses[i];
    std::printf("  %2zu  (%.3f, %.3f, %.3f rad)\n", i, h.x, h.y, h.theta);
  }
  for (std::size_t s = 0; s < plan.stops.size(); ++s) {
    const LocalizationStop& stop = plan.stops[s];
    std::printf("stop %zu at (%.3f, %.3f) in the start frame, %.3f along the way: %zu ruled out\n",
                s + 1, stop.point.x(), stop.point.y(), stop.route_length, stop.eliminated.size());
  }
  std::printf(
      "%s after %zu stops, path %.3f; lower bounds: %.3f to the nearest informative "
      "point%s, %.3f to tell every wrong hypothesis from the truth\n",
      plan.resolved ? "resolved" : plan.ended.c_str(), plan.stops.size(), plan.path_length,
      bound.distance, bound.optimal ? " (the optimum)" : "", bound.pairwise);
}

/// The picture's data: the first stop's overlay, U and random points (the planner's first
/// round: the same seed), the path and the bound.
DisambiguationPicture picture_of(const DisambiguateArgs& args, const PolygonMap& map,
                                 const MinimumDistancePlan& plan, int true_index,
                                 const TravelBound& bound) {
  const MinimumDistanceOptions options = planner_options(args);
  const PolygonSpaceOptions space = space_options(args);
  DisambiguationPicture picture;
  picture.title = fs::path(args.map).filename().string() + ": " + args.algorithm + ", " +
                  args.strategy + ", " + std::to_string(args.points) + " points, range " +
                  (std::isfinite(args.range) ? plot::number(args.range) : "unlimited");
  picture.caption = std::to_string(plan.hypotheses.size()) + " hypotheses, " +
                    std::to_string(plan.stops.size()) + " stops, path " +
                    plot::fixed(plan.path_length, 2) + ", lower bounds " +
                    plot::fixed(bound.distance, 2) + " (nearest informative point) and " +
                    plot::fixed(bound.pairwise, 2) + " (every wrong hypothesis told apart)" +
                    (plan.resolved ? ", resolved" : "");
  picture.map = map;
  picture.hypotheses = plan.hypotheses;
  picture.true_hypothesis = true_index;
  picture.remaining = plan.remaining;
  picture.path = whole_path(plan);
  for (const LocalizationStop& stop : plan.stops) picture.stops.push_back(stop.point);
  if (plan.hypotheses.size() >= 2) {
    const Area free_world = free_area(map);
    picture.overlay = make_overlay(free_world, plan.hypotheses);
    if (options.algorithm == SamplingAlgorithm::Ual) {
      picture.useful = useful_region(picture.overlay.oi, picture.overlay.internal_edges,
                                     space.range, space.samples_per_edge);
    }
    Rng rng(options.seed);
    const Region sampled =
        region_size(picture.useful) > 0.0 ? picture.useful : Region{picture.overlay.oi};
    picture.samples = sample_uniform(sampled, options.points, rng);
    if (std::isfinite(bound.distance)) picture.bound_point = bound.point;
  }
  return picture;
}

void write_outputs(const DisambiguateArgs& args, const PolygonMap& map,
                   const MinimumDistancePlan& plan, int true_index, const TravelBound& bound,
                   const nlohmann::json& out) {
  const fs::path dir(args.out);
  write_plan_json(args.out, out);
  const std::string json_path = (dir / "disambiguation.json").string();
  const std::string png_path = (dir / "disambiguation.png").string();
  plot::write_png(png_path, render_disambiguation(picture_of(args, map, plan, true_index, bound)));
  if (!args.json) std::printf("wrote %s and %s\n", png_path.c_str(), json_path.c_str());
}

/// The lower bound, or 0 (the optimum) for a start no other place matches.
TravelBound bound_for(const PolygonPlanningSpace& space, const std::vector<Pose2>& hypotheses,
                      int true_index) {
  if (hypotheses.size() < 2) {  // nothing to tell apart: no travel, optimally
    TravelBound none;
    none.distance = none.pairwise = 0.0;
    none.optimal = true;
    return none;
  }
  const double range = space.options().range;
  return travel_lower_bound(space, hypotheses, true_index, 0.0,
                            std::isfinite(range) ? range / 4.0 : kUnlimitedRange);
}

void run_on_polygons(const DisambiguateArgs& args) {
  const PolygonMap map = load_polygon_inputs(args);
  const Pose2 start = parse_pose(args.pose, "--pose");
  make_out_dir(args.out);
  const MinimumDistanceOptions options = planner_options(args);
  validate(options);
  const PolygonPlanningSpace space(free_area(map), space_options(args));
  const std::vector<Pose2> hypotheses = start_hypotheses(
      space.free_world(), start, {args.range, args.rotation, space.options().tolerance});
  const int true_index = find_pose(hypotheses, start);
  const MinimumDistancePlan plan = localize_with_minimum_travel(
      space, hypotheses, perfect_sensing(space.free_world(), start, hypotheses, args.range),
      options);
  const TravelBound bound = bound_for(space, hypotheses, true_index);
  const nlohmann::json out = polygon_plan_json(plan, true_index, bound);
  if (args.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_summary(plan, bound);
  }
  if (!args.out.empty()) write_outputs(args, map, plan, true_index, bound, out);
}

void run(const DisambiguateArgs& args, const GridDisambiguationSimulation& simulation) {
  if (is_polygon_map_input(args.map)) return run_on_polygons(args);
  run_disambiguate_on_grid(args, simulation);
}

}  // namespace

void add_disambiguate(CLI::App& app, const GridDisambiguationSimulation& simulation) {
  auto args = std::make_shared<DisambiguateArgs>();
  auto* cmd = app.add_subcommand(
      "disambiguate",
      "Where to drive, as little as possible, to tell look-alike places apart (seed 002)");
  cmd->add_option("--map", args->map,
                  "polygon map (YAML with a 'boundary': seed 002 exactly) or occupancy map "
                  "(map_server YAML: the engine in the loop) (- reads standard input)")
      ->required();
  auto* pose = cmd->add_option("--pose", args->pose,
                               "the robot's true start x,y,theta (m, m, rad): its view there is "
                               "simulated with a perfect sensor");
  auto* scan =
      cmd->add_option("--scan", args->scan,
                      "occupancy maps: a laser scan CSV taken at the start; prints the "
                      "hypotheses and the first stop to drive to (- reads standard input)");
  auto* readings = cmd->add_option("--readings", args->readings,
                                   "occupancy maps: sonar readings JSON taken at the start (the "
                                   "same, with --ring; - reads standard input)");
  pose->excludes(scan)->excludes(readings);
  scan->excludes(readings);
  cmd->add_option("--range", args->range,
                  "the sensor's range d (map units, > 0; inf or the default: unlimited)")
      ->check(positive_range());
  cmd->add_option("--algorithm", args->algorithm,
                  "col: sample all of OI; ual: sample its useful region U")
      ->check(CLI::IsMember({"col", "ual"}))
      ->capture_default_str();
  cmd->add_option("--strategy", args->strategy,
                  "weighted: info per distance from the start; hybrid: from where the robot is")
      ->check(CLI::IsMember({"weighted", "hybrid"}))
      ->capture_default_str();
  cmd->add_option("--points", args->points, "random points per round")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "seed of the random points")->capture_default_str();
  cmd->add_option("--threads", args->threads, "threads scoring the random points (same plan)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--rotation", args->rotation,
                "match the start view up to rotation too (default: the heading is known)");
  cmd->add_option("--ring", args->ring,
                  "occupancy maps: the sonar ring YAML (default: the "
                  "bundled wheelchair; - reads standard input)");
  cmd->add_option("--sensor", args->sensor,
                  "occupancy maps with --pose: the simulated sensor, sonar or laser")
      ->check(CLI::IsMember({"sonar", "laser"}))
      ->capture_default_str();
  cmd->add_option("--max-range", args->max_range,
                  "occupancy maps: the laser's max range (m), of --scan and the simulated laser")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "folder for disambiguation.png and disambiguation.json (created if missing)");
  cmd->add_flag("--json", args->json, "print JSON instead of the summary");
  read_stdin_at_most_once(cmd, {{"--map"}, {"--ring"}, {"--scan"}, {"--readings"}});
  cmd->callback([args, simulation] { run(*args, simulation); });
}

}  // namespace gridloc::cli
