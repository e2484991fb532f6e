// The checks a real laser scan's answer gets beyond its score.
#include "gridloc/engine/correlation/scan_checks.hpp"

#include "gridloc/grids/option_checks.hpp"
#include "gridloc/sensors/through_walls.hpp"

namespace gridloc {

void validate(const ScanChecks& checks) {
  require_non_negative(checks.through_wall_ratio, "scan checks", "through_wall_ratio");
  require_non_negative(checks.through_wall_margin_m, "scan checks", "through_wall_margin_m");
}

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
  if (through || edge) estimate.verdict = Verdict::NotLocalized;
}

}  // namespace gridloc
