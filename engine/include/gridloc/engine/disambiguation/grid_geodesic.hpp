#pragma once
/// Shortest paths inside a grid overlay's OI (the grid twin of seed 002's distance_OI): Dijkstra
/// over the OI cells, 8-connected, a diagonal step allowed only when both cells beside it are in
/// OI too, so a path never cuts a corner of the region.
#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "gridloc/engine/disambiguation/grid_overlay.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// Distances from one source cell to every OI cell, built once per source.
class GridGeodesic {
 public:
  /// `source` (start frame, m) must lie in an OI cell of `overlay`; throws gridloc::Error
  /// otherwise. Steps weigh resolution x {1, sqrt 2} (m).
  GridGeodesic(const GridOverlay& overlay, const Eigen::Vector2d& source);

  /// The length (m) of the shortest 8-connected path from the source cell's centre to the
  /// centre of the cell holding `target`; +infinity when that cell is not in OI.
  double distance_to(const Eigen::Vector2d& target) const;

  /// That path as cell centres (start frame, m) from the source cell's to the target cell's,
  /// keeping only the cells where it turns (collinear runs merged); its polyline length equals
  /// distance_to. Empty when the target cell is not in OI.
  std::vector<Eigen::Vector2d> path_to(const Eigen::Vector2d& target) const;

 private:
  /// The lattice index of the OI cell holding p, or -1.
  int oi_index(const Eigen::Vector2d& p) const;
  Eigen::Vector2d center_of(int index) const;
  /// The (column, row) step from lattice index `from` to `to`.
  std::pair<int, int> step_between(int from, int to) const;

  GridGeometry grid_;                ///< the overlay's lattice
  std::vector<std::uint8_t> in_oi_;  ///< the overlay's OI cells
  std::vector<double> distance_;     ///< per cell, from the source (+inf: unreached)
  std::vector<int> previous_;        ///< per cell, the cell before it on the path (-1: none)
};

}  // namespace gridloc
