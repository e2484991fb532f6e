// The checks a real laser scan's answer gets beyond its score.
#include "gridloc/engine/correlation/scan_checks.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/through_walls.hpp"

namespace gridloc {

void validate(const ScanChecks& checks) {
  require_non_negative(checks.through_wall_ratio, "scan checks", "through_wall_ratio");
  require_non_negative(checks.through_wall_margin_m, "scan checks", "through_wall_margin_m");
  require_share(checks.close_second_ratio, "scan checks", "close_second_ratio");
  require_non_negative(checks.close_second_m, "scan checks", "close_second_m");
  require_non_negative(checks.close_second_through_walls, "scan checks",
                       "close_second_through_walls");
  require_non_negative(checks.close_second_confidence, "scan checks", "close_second_confidence");
}

namespace {

/// A second place nearly as good as the winner, and the winner not clean (ScanChecks).
bool close_second(const Estimate& estimate, const ScanChecks& checks) {
  if (!(checks.close_second_ratio > 0.0) || estimate.alternatives.size() < 2 ||
      !(estimate.score > 0.0)) {
    return false;
  }
  const Pose2& winner = estimate.alternatives.front().pose;
  const bool near_as_good = std::any_of(
      estimate.alternatives.begin() + 1, estimate.alternatives.end(), [&](const Hypothesis& h) {
        return h.score >= checks.close_second_ratio * estimate.score &&
               std::hypot(h.pose.x - winner.x, h.pose.y - winner.y) > checks.close_second_m;
      });
  return near_as_good && estimate.through_walls >= checks.close_second_through_walls &&
         estimate.confidence < checks.close_second_confidence;
}

}  // namespace

void check_scan_answer(Estimate& estimate, const OccupancyMap& map, const RangeScan& scan,
                       const ScanChecks& checks) {
  validate(checks);
  if (checks.through_wall_ratio > 0.0) {
    estimate.through_walls =
        through_walls(map, scan, estimate.pose, checks.through_wall_margin_m).share();
  }
  if (estimate.verdict != Verdict::Localized) return;
  const bool through =
      checks.through_wall_ratio > 0.0 &&
      estimate.through_walls >= checks.through_wall_ratio * estimate.normalized_score;
  const bool edge = checks.edge_not_localized && estimate.on_window_edge;
  if (through || edge) {
    estimate.verdict = Verdict::NotLocalized;
  } else if (close_second(estimate, checks)) {
    estimate.verdict = Verdict::Ambiguous;
    estimate.ambiguous = true;
  }
}

}  // namespace gridloc
