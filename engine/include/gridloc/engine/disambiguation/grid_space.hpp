#pragma once
/// Seed 002 on an occupancy map (the grid twin): overlays on a start-frame lattice, shortest
/// paths by Dijkstra over OI's cells, and views as predicted noise-free scans compared
/// within a tolerance, so that hypotheses from the correlation engine (any heading, poses
/// good to a few cm) can be told apart.
#include <vector>

#include "gridloc/engine/disambiguation/grid_views.hpp"
#include "gridloc/engine/disambiguation/planning_space.hpp"
#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/grids/grid.hpp"

namespace gridloc {

struct GridSpaceOptions {
  double range = kUnlimitedRange;  ///< the sensor's range (m, > 0)
  ScanEquivalence equivalence;     ///< when two predicted scans are the same view
  /// The robot is no point: the overlay keeps only free cells this far (m, >= 0) from every
  /// occupied cell, so that routes and stops leave room for its footprint (the predicted
  /// views still read the whole map).
  double clearance_m = 0.0;
};

class GridPlanningSpace final : public PlanningSpace {
 public:
  /// Throws gridloc::Error for an empty map or a range that is not > 0.
  GridPlanningSpace(OccupancyMap map, const GridSpaceOptions& options = {});

  std::unique_ptr<StopOverlay> overlay(const std::vector<Pose2>& hypotheses,
                                       const Eigen::Vector2d& anchor) const override;
  std::vector<int> classes(const std::vector<Pose2>& hypotheses,
                           const Eigen::Vector2d& r) const override;

  const OccupancyMap& map() const { return map_; }
  /// The free cells at least clearance_m from every occupied cell (the others Occupied).
  const OccupancyMap& passable() const { return passable_; }
  const GridSpaceOptions& options() const { return options_; }

 private:
  OccupancyMap map_;
  OccupancyMap passable_;
  GridSpaceOptions options_;
};

}  // namespace gridloc
