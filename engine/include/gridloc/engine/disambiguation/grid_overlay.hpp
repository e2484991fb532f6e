#pragma once
/// The grid twin of seed 002's overlay arrangement (§IV, Figs 3-5, 7) on occupancy maps: a
/// lattice in the robot's start frame where a cell belongs to hypothesis i's map when its centre,
/// seen from hypothesis i, falls on a Free cell of the map; OI, the 4-connected component of the
/// cells free in every map that holds the robot; the internal cells on OI's border (beyond them
/// some hypothesis has free space); and U, the OI cells that see an internal cell within range.
///
/// Frames: a hypothesis is the robot's start pose in the world, h = (x, y, theta); start-frame
/// point r lies at world point to_world(h, r) = R(theta) r + (x, y) (region.hpp). The lattice is
/// axis-aligned in the start frame (yaw 0), its cell corners at integer multiples of the map's
/// resolution, row index growing with start-frame y.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

/// The overlay on a start-frame lattice; every per-cell vector has grid.size() bytes, row-major
/// (index = iy * width + ix), 1 for a member and 0 otherwise.
struct GridOverlay {
  GridGeometry grid;                   ///< the start-frame lattice (resolution = the map's, yaw 0)
  std::vector<Pose2> hypotheses;       ///< the robot's start pose in the world under each
  double range = 0.0;                  ///< the sensor's range (m) U was built for; +inf: unlimited
  Cell anchor_cell;                    ///< the lattice cell of the anchor OI was grown from
  std::vector<std::uint8_t> in_any;    ///< free in at least one hypothesis's map
  std::vector<std::uint8_t> in_oi;     ///< in OI (free in every map, connected to the anchor)
  std::vector<std::uint8_t> internal;  ///< OI cells with a 4-neighbour outside OI in_any
  std::vector<std::uint8_t> useful;    ///< U: OI cells that see an internal cell within range
  int oi_count = 0;                    ///< cells in OI
  int internal_count = 0;              ///< internal cells
  int useful_count = 0;                ///< cells in U

  /// The lattice cell holding start-frame point p (may lie outside the lattice).
  Cell cell_of(const Eigen::Vector2d& p) const;
  /// The start-frame centre of lattice cell `cell` (m).
  Eigen::Vector2d cell_center(const Cell& cell) const;
  /// Whether start-frame point p lies in an OI cell.
  bool oi_contains(const Eigen::Vector2d& p) const;
};

/// Builds the overlay of `map` under `hypotheses` (seed 002 §IV-C steps 4-5, §IV-D steps 5-6).
/// The lattice spans the intersection of the maps' free-cell bounding boxes seen in the start
/// frame, plus one cell each side (nothing outside can be in OI). OI grows 4-connected from
/// the anchor's cell (start frame, m). U casts rays from every internal cell centre through OI
/// cells (128 directions, split until neighbouring rays end at most a cell apart), marking
/// each crossed cell whose centre is within `range` (m; +inf: unlimited) of the ray's start.
/// Throws gridloc::Error for an empty map or hypothesis list, a pose or anchor that is not
/// finite, a range that is not positive, or an anchor whose cell is not free in every map and
/// has no such cell within 3 cells (then the nearest is OI's seed: an estimate a hair inside a
/// wall).
GridOverlay make_grid_overlay(const OccupancyMap& map, const std::vector<Pose2>& hypotheses,
                              double range,
                              const Eigen::Vector2d& anchor = Eigen::Vector2d::Zero());

/// `count` start-frame points drawn uniformly over the OI cells (or over U when `useful`), each
/// jittered uniformly inside its cell (seed 002 §IV-A random points, §IV-D step 7). Empty when
/// the set is empty; throws gridloc::Error for a negative count.
std::vector<Eigen::Vector2d> sample_overlay_cells(const GridOverlay& overlay, bool useful,
                                                  int count, Rng& rng);

}  // namespace gridloc
