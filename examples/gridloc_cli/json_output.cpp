#include <cmath>

#include "commands.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc::cli {

nlohmann::json number_or_null(double v) {
  return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
}

nlohmann::json to_json(const Pose2& p) {
  return {{"x", p.x}, {"y", p.y}, {"theta", p.theta}};
}

nlohmann::json to_json(const Estimate& e) {
  nlohmann::json alternatives = nlohmann::json::array();
  for (const auto& h : e.alternatives) {
    alternatives.push_back({{"pose", to_json(h.pose)}, {"score", h.score}});
  }
  nlohmann::json covariance = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    covariance.push_back({e.covariance(r, 0), e.covariance(r, 1), e.covariance(r, 2)});
  }
  return {
      {"pose", to_json(e.pose)},
      {"theta_deg", rad2deg(e.pose.theta)},
      {"score", e.score},
      {"normalized_score", e.normalized_score},
      {"second_score", e.second_score},
      {"confidence", e.confidence},
      {"confidence_parts",
       {{"fit", e.confidence_parts.fit},
        {"agreement", e.confidence_parts.agreement},
        {"distinctness", e.confidence_parts.distinctness},
        {"sharpness", e.confidence_parts.sharpness}}},
      {"ambiguous", e.ambiguous},
      {"verdict", to_string(e.verdict)},
      {"on_window_edge", e.on_window_edge},
      {"alternatives", alternatives},
      {"covariance", covariance},  // x, y, theta (m^2, m rad, rad^2), world frame
      {"std",
       {{"x", std::sqrt(e.covariance(0, 0))},
        {"y", std::sqrt(e.covariance(1, 1))},
        {"theta", std::sqrt(e.covariance(2, 2))}}},
      {"stats",
       {{"poses_scored", e.stats.poses_scored},
        {"cells_scored", e.stats.cells_scored},
        {"levels", e.stats.levels},
        {"proven_optimal", e.stats.proven_optimal},
        {"upper_bound", std::isnan(e.stats.upper_bound) ? nlohmann::json(nullptr)
                                                        : nlohmann::json(e.stats.upper_bound)}}}};
}

}  // namespace gridloc::cli
