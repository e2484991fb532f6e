#include "gridloc/engine/disambiguation/travel_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

/// The way to the nearest lattice point whose classes pass `informative`, walking nearest first.
template <class Informative>
double nearest_where(const std::vector<LatticePoint>& points, const Informative& informative,
                     Eigen::Vector2d& where) {
  for (const LatticePoint& lattice : points) {
    if (informative(lattice.point)) {
      where = lattice.point;
      return lattice.distance;
    }
  }
  return std::numeric_limits<double>::infinity();
}

double lattice_step(const StopOverlay& overlay, double step, double max_step) {
  if (step > 0.0) return step;
  return std::min(max_step, std::sqrt(std::max(overlay.oi_size(), 1e-12) / kLatticePoints));
}

/// Telling wrong hypothesis j from the truth: until then their views agree, so the robot has
/// stayed where both maps are free, in the OI of the pair (which holds the OI of all).
double pair_distance(const PlanningSpace& space, const Pose2& truth, const Pose2& wrong,
                     double step, double max_step) {
  const std::vector<Pose2> pair{truth, wrong};
  const std::unique_ptr<StopOverlay> overlay = space.overlay(pair);
  const std::vector<LatticePoint> points =
      points_by_distance(*overlay, lattice_step(*overlay, step, max_step));
  Eigen::Vector2d where;
  return nearest_where(
      points, [&](const Eigen::Vector2d& p) { return space.classes(pair, p)[1] != 0; }, where);
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
  bound.step = lattice_step(*overlay, step, max_step);
  bound.optimal = hypotheses.size() == 2;
  const std::vector<LatticePoint> points = points_by_distance(*overlay, bound.step);
  bound.points = static_cast<int>(points.size());
  // Until the first elimination every view agrees: the robot is in the OI of all.
  bound.distance = nearest_where(
      points,
      [&](const Eigen::Vector2d& p) {
        const std::vector<int> classes = space.classes(hypotheses, p);
        return std::any_of(classes.begin(), classes.end(), [](int c) { return c != 0; });
      },
      bound.point);
  if (truth < 0) return bound;
  bound.pairwise = 0.0;
  for (std::size_t j = 0; j < hypotheses.size(); ++j) {
    if (static_cast<int>(j) == truth) continue;
    bound.pairwise =
        std::max(bound.pairwise, pair_distance(space, hypotheses[static_cast<std::size_t>(truth)],
                                               hypotheses[j], step, max_step));
  }
  return bound;
}

}  // namespace gridloc
