#include "gridloc/engine/disambiguation/travel_bound.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr double kLatticePoints = 4000.0;

struct LatticePoint {
  Eigen::Vector2d point;
  double distance = 0.0;
};

/// The lattice points OI reaches, nearest first (ties: lattice order).
std::vector<LatticePoint> points_by_distance(const StopOverlay& overlay, double step) {
  const std::unique_ptr<OverlayPaths> from_start = overlay.paths_from(Eigen::Vector2d::Zero());
  std::vector<LatticePoint> points;
  for (const Eigen::Vector2d& point : overlay.lattice(step)) {
    const double distance = from_start->distance_to(point);
    if (std::isfinite(distance)) points.push_back({point, distance});
  }
  std::stable_sort(points.begin(), points.end(), [](const LatticePoint& a, const LatticePoint& b) {
    return a.distance < b.distance;
  });
  return points;
}

/// Walks the points nearest first until every wrong hypothesis has been told from the truth
/// (or, without the truth, until the first informative point).
void walk_lattice(const PlanningSpace& space, const std::vector<Pose2>& hypotheses, int truth,
                  const std::vector<LatticePoint>& points, TravelBound& bound) {
  std::vector<bool> told(hypotheses.size(), false);
  std::size_t untold = truth >= 0 ? hypotheses.size() - 1 : 0;
  if (truth >= 0) told[static_cast<std::size_t>(truth)] = true;
  for (const LatticePoint& lattice : points) {
    if (std::isfinite(bound.distance) && untold == 0) break;
    const std::vector<int> classes = space.classes(hypotheses, lattice.point);
    const bool informative =
        std::any_of(classes.begin(), classes.end(), [](int c) { return c != 0; });
    if (informative && !std::isfinite(bound.distance)) {
      bound.distance = lattice.distance;
      bound.point = lattice.point;
    }
    for (std::size_t j = 0; truth >= 0 && j < hypotheses.size(); ++j) {
      if (told[j] || classes[j] == classes[static_cast<std::size_t>(truth)]) continue;
      told[j] = true;
      --untold;
      bound.pairwise = lattice.distance;  // nearest first: the last one told is the farthest
    }
  }
  if (truth >= 0 && untold > 0) bound.pairwise = std::numeric_limits<double>::infinity();
}

}  // namespace

TravelBound travel_lower_bound(const PlanningSpace& space, const std::vector<Pose2>& hypotheses,
                               int truth, double step, double max_step) {
  if (hypotheses.size() < 2) throw Error("travel bound: needs at least two hypotheses");
  if (!(step >= 0.0) || !std::isfinite(step)) throw Error("travel bound: step must be >= 0");
  if (!(max_step > 0.0)) throw Error("travel bound: max_step must be > 0");
  if (truth < -1 || truth >= static_cast<int>(hypotheses.size())) {
    throw Error("travel bound: the truth's index " + std::to_string(truth) +
                " names no hypothesis");
  }
  const std::unique_ptr<StopOverlay> overlay = space.overlay(hypotheses);
  TravelBound bound;
  bound.step =
      step > 0.0
          ? step
          : std::min(max_step, std::sqrt(std::max(overlay->oi_size(), 1e-12) / kLatticePoints));
  bound.optimal = hypotheses.size() == 2;
  const std::vector<LatticePoint> points = points_by_distance(*overlay, bound.step);
  bound.points = static_cast<int>(points.size());
  walk_lattice(space, hypotheses, truth, points, bound);
  return bound;
}

}  // namespace gridloc
