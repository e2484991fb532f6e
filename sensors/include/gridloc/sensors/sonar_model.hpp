#pragma once
/// The oriented sonar-cone model of seed 001 §3 and its rasterization into a local grid.
#include <vector>

#include "gridloc/sensors/local_grid.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// How a local grid is made for heading theta: `Oriented` discretizes the model already
/// rotated by theta (seed 001 eq. 3); `Turned` builds the grid at theta = 0 and moves each
/// cell to its rotated position (the paper's baseline, which loses and doubles cells).
enum class LocalModel { Oriented, Turned };

struct SonarModelOptions {
  /// Radial depth of an arc, in cells on each side of the echo range: 0 is seed 001's
  /// one-cell arc; 0.5 (default) also marks the arcs half a cell before and after it, so that
  /// an echo whose range noise crosses a cell boundary still meets the obstacle's contour
  /// cell. The arc's n1 cells still share +1/n1.
  double arc_depth_cells = 0.5;
};

/// Rasterizes the readings of `ring` for a robot heading `theta` (rad) into cells of size
/// `resolution` (m), the robot centre lying `centre` (m) from the centre of cell (0, 0)
/// (zero on the search lattice; sub-cell offsets serve refinement). Per cone with an echo at range
/// d: the n1 cells of the 8-connected arc at d get +1/n1 and the n2 cells of the free sector before
/// it get -1/n2; a reading with no echo (d >= max_range) gives its free sector up to max_range
/// only. The footprint's n cells get -N/n (N = number of sonars). `options.arc_depth_cells` widens
/// arcs radially. Overlap rule: an arc cell of any cone stays occupied (arc values of several cones
/// add, free values on it are dropped); free values of several cones add; the footprint overrides
/// everything. Readings must have passed validate_readings(). A sonar flagged in `rejected`
/// (empty = none; see filter_echoes) draws no cone at all, neither arc nor free sector, and N
/// counts only the others: the grid is the one of a ring without that sonar.
SparseLocalGrid rasterize_oriented(const SonarRing& ring, const std::vector<double>& ranges,
                                   double theta, double resolution,
                                   const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                                   const SonarModelOptions& options = {},
                                   const std::vector<bool>& rejected = {});

/// The paper's "turned" grid: rasterize at theta = 0, then move every cell centre by the
/// rotation theta and round to the nearest cell; a cell hit twice keeps the later value.
SparseLocalGrid rasterize_turned(const SonarRing& ring, const std::vector<double>& ranges,
                                 double theta, double resolution,
                                 const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                                 const SonarModelOptions& options = {},
                                 const std::vector<bool>& rejected = {});

/// Dispatches on `model`.
SparseLocalGrid rasterize(const SonarRing& ring, const std::vector<double>& ranges, double theta,
                          double resolution, LocalModel model,
                          const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                          const SonarModelOptions& options = {},
                          const std::vector<bool>& rejected = {});

}  // namespace gridloc
