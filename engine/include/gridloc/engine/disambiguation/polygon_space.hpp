#pragma once
/// Seed 002 as the paper has it: a polygon map, a perfect range sensor of range d, exact
/// views compared up to translation, overlays clipped by Boost.Geometry, shortest paths on
/// the visibility graph, U from weak visibility polygons.
#include <vector>

#include "gridloc/engine/disambiguation/planning_space.hpp"
#include "gridloc/engine/disambiguation/range_view.hpp"
#include "gridloc/engine/disambiguation/region.hpp"

namespace gridloc {

struct PolygonSpaceOptions {
  double range = kUnlimitedRange;  ///< the sensor's range d (> 0)
  double tolerance = 1e-6;         ///< of same_view()
  int samples_per_edge = 16;       ///< of useful_region()'s weak visibility polygons (>= 2)
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const PolygonSpaceOptions& options);

class PolygonPlanningSpace final : public PlanningSpace {
 public:
  /// Throws gridloc::Error for bad options.
  PolygonPlanningSpace(Area free_world, const PolygonSpaceOptions& options = {});

  std::unique_ptr<StopOverlay> overlay(const std::vector<Pose2>& hypotheses,
                                       const Eigen::Vector2d& anchor) const override;
  std::vector<int> classes(const std::vector<Pose2>& hypotheses,
                           const Eigen::Vector2d& r) const override;

  const Area& free_world() const { return free_world_; }
  const PolygonSpaceOptions& options() const { return options_; }

 private:
  Area free_world_;
  PolygonSpaceOptions options_;
};

/// The views predicted at start-frame point `r` under each hypothesis.
std::vector<RangeView> predicted_views(const Area& free_world, const std::vector<Pose2>& hypotheses,
                                       const Eigen::Vector2d& r, double range);

}  // namespace gridloc
