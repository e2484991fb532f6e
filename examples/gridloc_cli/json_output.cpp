#include <cmath>

#include "commands.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc::cli {

nlohmann::json number_or_null(double value) {
  return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
}

nlohmann::json to_json(const Pose2& pose) {
  return {{"x", pose.x}, {"y", pose.y}, {"theta", pose.theta}};
}

nlohmann::json to_json(const Estimate& estimate) {
  nlohmann::json alternatives = nlohmann::json::array();
  for (const auto& hypothesis : estimate.alternatives) {
    nlohmann::json alternative = {{"pose", to_json(hypothesis.pose)}, {"score", hypothesis.score}};
    if (!std::isnan(hypothesis.weight)) alternative["weight"] = hypothesis.weight;
    alternatives.push_back(std::move(alternative));
  }
  nlohmann::json covariance = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    covariance.push_back(
        {estimate.covariance(r, 0), estimate.covariance(r, 1), estimate.covariance(r, 2)});
  }
  nlohmann::json json = {
      {"pose", to_json(estimate.pose)},
      {"theta_deg", rad2deg(estimate.pose.theta)},
      {"score", estimate.score},
      {"normalized_score", estimate.normalized_score},
      {"second_score", estimate.second_score},
      {"second_below_floor", estimate.second_below_floor},
      {"confidence", estimate.confidence},
      {"confidence_parts",
       {{"fit", estimate.confidence_parts.fit},
        {"agreement", estimate.confidence_parts.agreement},
        {"distinctness", estimate.confidence_parts.distinctness},
        {"sharpness", estimate.confidence_parts.sharpness}}},
      {"ambiguous", estimate.ambiguous},
      {"verdict", to_string(estimate.verdict)},
      {"on_window_edge", estimate.on_window_edge},
      {"rises_past_window_edge", estimate.rises_past_window_edge},
      {"alternatives", alternatives},
      {"covariance", covariance},  // x, y, theta (m^2, m rad, rad^2), world frame
      {"std",
       {{"x", std::sqrt(estimate.covariance(0, 0))},
        {"y", std::sqrt(estimate.covariance(1, 1))},
        {"theta", std::sqrt(estimate.covariance(2, 2))}}},
      {"stats",
       {{"poses_scored", estimate.stats.poses_scored},
        {"cells_scored", estimate.stats.cells_scored},
        {"levels", estimate.stats.levels},
        {"proven_optimal", estimate.stats.proven_optimal},
        {"upper_bound", std::isnan(estimate.stats.upper_bound)
                            ? nlohmann::json(nullptr)
                            : nlohmann::json(estimate.stats.upper_bound)}}}};
  // A laser scan's whole-map answer: the share of its returns seen through a wall there.
  if (!std::isnan(estimate.through_walls)) json["through_walls"] = estimate.through_walls;
  return json;
}

}  // namespace gridloc::cli
