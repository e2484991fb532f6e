#pragma once
/// Visibility sectors (seed 000, Lee, Amato and Fellers): the free space of a polygon map cut
/// into the regions from which the same set of environment vertices is visible, each with a
/// label of characteristic points (M local maximum, m local minimum, D discontinuity,
/// c connection) in counter-clockwise order from east.
///
/// Seed 000 builds the sectors exactly, as the faces of the overlay of every vertex's
/// visibility polygon. This is the documented robust alternative: the free space is sampled
/// on a grid of `cell_m`, each cell centre gets its visible-vertex set (exact segment tests,
/// so no arrangement of nearly parallel segments can go wrong), and a sector is a
/// 4-connected region of cells with one set. A sector thinner than a cell can be missed; its
/// area goes to a neighbour. A sector's label is the label of a dense noise-free scan (3600
/// beams, heading 0) from its most interior cell.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/engine/sectors/scan_label.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

struct SectorOptions {
  double cell_m = 0.05;    ///< sampling cell of the free space (m)
  int label_beams = 3600;  ///< beams of the dense scan that gives a sector its label
  /// N_min counts only cells at least this far (m) from every wall: where the robot can be.
  double clearance_m = 0.3;
  ScanLabelOptions label;  ///< for the dense scan (noise-free: median_window 1)
  /// Bound the sampling grid (max_cells) and its visible-vertex sets (max_memory_mb), checked
  /// before they are allocated.
  ResourceLimits limits;
};

struct Sector {
  std::string label;               ///< counter-clockwise from east
  std::vector<int> features;       ///< per character: the vertex of an M or D, else -1
  std::vector<int> visible;        ///< indices into SectorMap::vertices
  Eigen::Vector2d representative;  ///< the most interior cell's centre (world, m)
  int cells = 0;
  double area_m2 = 0.0;
  /// Another sector's label is this one turned: a scan cannot tell them apart (seed 000
  /// §4.1).
  bool ambiguous = false;
  /// Seed 000 eq. (10)-(11): readings per 360 deg that guarantee 3 (resp. 2) on every edge
  /// seen from anywhere in the sector: 6 pi / alpha and 4 pi / alpha, alpha the smallest
  /// angle an edge with both ends visible subtends over the sector's cells at least
  /// SectorOptions::clearance_m from the walls; 0 when no cell is that far.
  int n_min = 0;
  int n_min_two = 0;
};

struct SectorMap {
  PolygonMap map;
  std::vector<Eigen::Vector2d> vertices;  ///< the boundary's, then each obstacle's
  std::vector<Sector> sectors;
  GridGeometry grid;           ///< the sampling grid
  std::vector<int> sector_of;  ///< per grid cell: its sector, or -1 outside the free space
  /// The sector of a world point, or -1.
  int sector_at(const Eigen::Vector2d& p) const;
  /// Seed 000 eq. (11) for the environment: the largest n_min_two of all sectors.
  int n_min_two() const;
};

/// Computes the sectors; throws gridloc::Error for bad options.
SectorMap compute_sectors(const PolygonMap& map, const SectorOptions& options = {});

/// A noise-free scan of the polygon map from `pose` (beam k at angle 2 pi k / beams, robot
/// frame), max range `max_range`.
RangeScan polygon_scan(const PolygonMap& map, const Pose2& pose, int beams, double max_range);

}  // namespace gridloc
