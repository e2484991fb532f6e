#include "gridloc/engine/disambiguation/travel_bound.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr double kLatticePoints = 4000.0;

}  // namespace

TravelBound travel_lower_bound(const PlanningSpace& space, const std::vector<Pose2>& hypotheses,
                               double step, double max_step) {
  if (hypotheses.size() < 2) throw Error("travel bound: needs at least two hypotheses");
  if (!(step >= 0.0) || !std::isfinite(step)) throw Error("travel bound: step must be >= 0");
  if (!(max_step > 0.0)) throw Error("travel bound: max_step must be > 0");
  const std::unique_ptr<StopOverlay> overlay = space.overlay(hypotheses);
  TravelBound bound;
  bound.step =
      step > 0.0
          ? step
          : std::min(max_step, std::sqrt(std::max(overlay->oi_size(), 1e-12) / kLatticePoints));
  bound.optimal = hypotheses.size() == 2;
  const std::unique_ptr<OverlayPaths> from_start = overlay->paths_from(Eigen::Vector2d::Zero());
  const std::vector<Eigen::Vector2d> lattice = overlay->lattice(bound.step);
  bound.points = static_cast<int>(lattice.size());
  for (const Eigen::Vector2d& point : lattice) {
    const double distance = from_start->distance_to(point);
    if (!(distance < bound.distance)) continue;  // only a nearer point can lower the bound
    if (space.info(hypotheses, point) > 0.0) {
      bound.distance = distance;
      bound.point = point;
    }
  }
  return bound;
}

}  // namespace gridloc
