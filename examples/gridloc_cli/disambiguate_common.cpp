#include "disambiguate_common.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "commands.hpp"
#include "gridloc/engine/disambiguation/region.hpp"
#include "gridloc/grids/error.hpp"
#include "output_files.hpp"

namespace gridloc::cli {
namespace {

nlohmann::json points_json(const std::vector<Eigen::Vector2d>& points) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Eigen::Vector2d& p : points) rows.push_back({{"x", p.x()}, {"y", p.y()}});
  return rows;
}

nlohmann::json stops_json(const MinimumDistancePlan& plan) {
  nlohmann::json stops = nlohmann::json::array();
  for (const LocalizationStop& stop : plan.stops) {
    stops.push_back({{"x", stop.point.x()},
                     {"y", stop.point.y()},
                     {"info", stop.info},
                     {"value", stop.value},
                     {"route_length_m", stop.route_length},
                     {"sampled", stop.sampled},
                     {"useful", stop.useful},
                     {"eliminated", stop.eliminated}});
  }
  return stops;
}

/// The path under each standing hypothesis, in the world.
nlohmann::json world_paths(const MinimumDistancePlan& plan) {
  nlohmann::json world = nlohmann::json::array();
  for (const int index : plan.remaining) {
    world.push_back({{"hypothesis", index}, {"path", points_json(world_path(plan, index))}});
  }
  return world;
}

}  // namespace

MinimumDistanceOptions planner_options(const DisambiguateArgs& args) {
  MinimumDistanceOptions options;
  options.algorithm = args.algorithm == "col" ? SamplingAlgorithm::Col : SamplingAlgorithm::Ual;
  options.strategy =
      args.strategy == "weighted" ? DistanceStrategy::Weighted : DistanceStrategy::Hybrid;
  options.points = args.points;
  options.seed = args.seed;
  options.threads = args.threads;
  return options;
}

nlohmann::json plan_json(const MinimumDistancePlan& plan, int true_index) {
  nlohmann::json hypotheses = nlohmann::json::array(), eliminated = nlohmann::json::array(),
                 refit = nlohmann::json::array();
  for (const Pose2& h : plan.hypotheses) hypotheses.push_back(to_json(h));
  for (const Pose2& h : plan.refit) refit.push_back(to_json(h));
  for (const LocalizationStop& stop : plan.stops) eliminated.push_back(stop.eliminated);
  const auto& left = plan.remaining;
  const bool survived = std::find(left.begin(), left.end(), true_index) != left.end();
  return {{"hypotheses", hypotheses},
          {"true_hypothesis", true_index},
          {"path", points_json(whole_path(plan))},
          {"path_world", world_paths(plan)},
          {"path_length_m", plan.path_length},
          {"stops", plan.stops.size()},
          {"stop_details", stops_json(plan)},
          {"eliminated", eliminated},
          {"remaining", plan.remaining},
          {"resolved", plan.resolved},
          {"refit_hypotheses", refit},
          {"ended", plan.ended},
          {"true_hypothesis_survived",
           true_index >= 0 ? nlohmann::json(survived) : nlohmann::json(nullptr)}};
}

void make_out_dir(const std::string& out) {
  if (!out.empty()) output_folder(out);
}

void write_plan_json(const std::string& out_dir, const nlohmann::json& out) {
  write_json_file(std::filesystem::path(out_dir) / "disambiguation.json", out, "the plan");
}

}  // namespace gridloc::cli
