#include "gridloc/engine/disambiguation/grid_space.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/engine/disambiguation/grid_geodesic.hpp"
#include "gridloc/engine/disambiguation/grid_overlay.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/likelihood_field.hpp"

namespace gridloc {
namespace {

class GridPaths final : public OverlayPaths {
 public:
  GridPaths(const GridOverlay& overlay, const Eigen::Vector2d& source)
      : geodesic_(overlay, source) {}
  double distance_to(const Eigen::Vector2d& target) const override {
    return geodesic_.distance_to(target);
  }
  std::vector<Eigen::Vector2d> path_to(const Eigen::Vector2d& target) const override {
    return geodesic_.path_to(target);
  }

 private:
  GridGeodesic geodesic_;
};

class GridStopOverlay final : public StopOverlay {
 public:
  explicit GridStopOverlay(GridOverlay overlay) : overlay_(std::move(overlay)) {}

  std::vector<Eigen::Vector2d> sample(SamplingAlgorithm algorithm, int count, Rng& rng,
                                      bool& from_useful) const override {
    from_useful = algorithm == SamplingAlgorithm::Ual && overlay_.useful_count > 0;
    return sample_overlay_cells(overlay_, from_useful, count, rng);
  }

  /// The centres of every k-th OI cell in each direction, k = step / resolution (>= 1).
  std::vector<Eigen::Vector2d> lattice(double step) const override {
    const GridGeometry& grid = overlay_.grid;
    const int stride = std::max(1, static_cast<int>(std::floor(step / grid.resolution)));
    std::vector<Eigen::Vector2d> points;
    for (int iy = 0; iy < grid.height; iy += stride) {
      for (int ix = 0; ix < grid.width; ix += stride) {
        if (overlay_.in_oi[grid.index(ix, iy)] != 0)
          points.push_back(overlay_.cell_center({ix, iy}));
      }
    }
    return points;
  }

  double oi_size() const override {
    return overlay_.oi_count * overlay_.grid.resolution * overlay_.grid.resolution;
  }

  bool oi_contains(const Eigen::Vector2d& p) const override { return overlay_.oi_contains(p); }

  /// A source outside OI (the anchor snapped to OI's nearest cell) starts from that cell.
  std::unique_ptr<OverlayPaths> paths_from(const Eigen::Vector2d& source) const override {
    const bool inside = overlay_.oi_contains(source);
    return std::make_unique<GridPaths>(
        overlay_, inside ? source : overlay_.cell_center(overlay_.anchor_cell));
  }

 private:
  GridOverlay overlay_;
};

/// `map` with the free cells nearer than `clearance_m` to an occupied cell made Occupied.
OccupancyMap passable_cells(const OccupancyMap& map, double clearance_m) {
  OccupancyMap passable = map;
  if (clearance_m <= 0.0) return passable;
  const double cells = clearance_m / map.geometry.resolution;
  const std::vector<double> squared = squared_cell_distances(map);
  for (std::size_t i = 0; i < passable.cells.size(); ++i) {
    if (passable.cells[i] == CellState::Free && squared[i] < cells * cells) {
      passable.cells[i] = CellState::Occupied;
    }
  }
  return passable;
}

}  // namespace

GridPlanningSpace::GridPlanningSpace(OccupancyMap map, const GridSpaceOptions& options)
    : map_(std::move(map)), options_(options) {
  if (map_.width() <= 0 || map_.height() <= 0) throw Error("disambiguation: the map is empty");
  if (!(options_.range > 0.0)) {
    throw Error("disambiguation: range must be > 0 (got a non-positive or NaN value)");
  }
  if (!(options_.clearance_m >= 0.0) || !std::isfinite(options_.clearance_m)) {
    throw Error("disambiguation: clearance must be a finite number of metres >= 0");
  }
  passable_ = passable_cells(map_, options_.clearance_m);
}

std::unique_ptr<StopOverlay> GridPlanningSpace::overlay(const std::vector<Pose2>& hypotheses,
                                                        const Eigen::Vector2d& anchor) const {
  return std::make_unique<GridStopOverlay>(
      make_grid_overlay(passable_, hypotheses, options_.range, anchor));
}

std::vector<int> GridPlanningSpace::classes(const std::vector<Pose2>& hypotheses,
                                            const Eigen::Vector2d& r) const {
  return scan_classes(map_, hypotheses, r, options_.range, options_.equivalence);
}

}  // namespace gridloc
