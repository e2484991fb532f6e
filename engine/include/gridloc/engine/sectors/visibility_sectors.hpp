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

#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

/// What CONSTRUCT SCAN LABEL (seed 000 §3.2) needs to read a noisy scan.
struct ScanLabelOptions {
  /// A jump between neighbouring readings larger than eps_abs_m + eps_rel * (nearer range) is
  /// a discontinuity (seed 000's epsilon_T, which it leaves open).
  double eps_abs_m = 0.3;
  double eps_rel = 0.15;
  /// Readings are median-filtered over this many beams first (odd, 1 = off). Seed 003 (ch. VI B)
  /// smooths its real IR data with a moving average over +-5 readings; a median removes the
  /// same spikes but keeps the jumps that D and c need.
  int median_window = 3;
  /// A local maximum and minimum of a continuous run that differ by less than this (m) are
  /// noise and dropped in pairs, the flattest first.
  double prominence_m = 0.05;
  /// Runs of at most this many beams without return, between two returns that continue each
  /// other (no discontinuity), are dropouts and are bridged (0 = off).
  int bridge_beams = 3;
};

/// A scan's label: one character per characteristic point, with the beam it was read at.
struct ScanLabel {
  std::string label;
  std::vector<int> beam;  ///< per character
};

/// CONSTRUCT SCAN LABEL of seed 000 §3.2 with its two slips fixed (the loop visits each beam
/// once; the two readings of a jump are D and c, never also m or M), the readings smoothed and
/// extrema of less than prominence_m dropped. Beams without return are "far" (a jump to them
/// is a discontinuity). The label starts at beam 0. Throws gridloc::Error for a scan that
/// fails validate() or bad options.
ScanLabel construct_scan_label(const RangeScan& scan, const ScanLabelOptions& options = {});

/// Whether `a` equals `b` turned: a cyclic shift of it. `shift` receives the k with
/// a[i] == b[(i + k) % n].
bool cyclic_equal(const std::string& a, const std::string& b, int* shift = nullptr);

struct SectorOptions {
  double cell_m = 0.05;    ///< sampling cell of the free space (m)
  int label_beams = 3600;  ///< beams of the dense scan that gives a sector its label
  /// N_min counts only cells at least this far (m) from every wall: where the robot can be.
  double clearance_m = 0.3;
  ScanLabelOptions label;  ///< for the dense scan (noise-free: median_window 1)
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

namespace gridloc {

struct SectorLocalizationOptions {
  ScanLabelOptions label;
  /// Labels are matched up to a turn and up to this many deleted neighbouring M m pairs (at
  /// most one from the scan's label, the rest from the sector's): shallow extrema that a
  /// noisy or coarse scan cannot resolve, or that move with the position inside a sector,
  /// which seed 000's exact match would turn into "no sector".
  int max_deleted_pairs = 3;
  /// Beams on each side of an M reading fitted with a line to locate its vertex (seed 000
  /// eqs. (6)-(9) use 4).
  int line_points = 4;
  /// A candidate pose more than 0.3 m or 15 deg from the winner whose residual is within this
  /// (m) of the winner's makes the fix ambiguous.
  double ambiguity_residual_m = 0.02;
  /// A beam's range difference counts at most this much (m) in SectorFix::residual_m: a few
  /// beams on a notch tell a room from its turned twin, where a median would ignore them,
  /// and clutter the map lacks costs a bounded amount.
  double residual_cap_m = 0.3;
  /// A rough pose (from located corners, before the polish) whose residual on a quarter of the
  /// beams exceeds this (m) is scored unpolished: the scan refutes it anyway.
  double rough_residual_m = 0.2;
  /// Also match the scan's D c skeleton (its jumps) against the sectors', the extrema between
  /// jumps free to differ: partial views of far or short edges (seed 000 §4.2) still localize.
  bool skeleton_matching = true;
  /// Neighbouring D c pairs the skeleton match may leave out of one side: a grazing wall's
  /// false jump, a narrow gap between two beams.
  int max_deleted_jumps = 1;
  /// Also place the winner's located vertices on every look-alike set of map vertices and
  /// score those poses: a look-alike place whose sector's label differs slightly is then still
  /// found, so the fix says "ambiguous" instead of answering one of the two.
  bool lookalike_search = true;
};

/// What localize_in_sectors() found.
struct SectorFix {
  bool found = false;
  int sector = -1;
  Pose2 pose;
  /// How loose the winning match was: the M m pairs seed 000's match left out of the labels
  /// (0 to max_deleted_pairs); above max_deleted_pairs, a skeleton match (max_deleted_pairs +
  /// 1 + the D c pairs it left out) or a look-alike placement (one more than the match it
  /// started from).
  int deleted_pairs = 0;
  int matched_m = 0;  ///< located corners (M, and D for skeleton matches) the pose was fitted to
  /// Mean over the beams of |measured - expected range| at `pose`, each capped at
  /// SectorLocalizationOptions::residual_cap_m (m): how well the map explains the scan there.
  double residual_m = 0.0;
  /// Matches (sector and turn) that gave a pose: the winner has the smallest residual.
  int candidates = 0;
  /// A candidate pose more than 0.3 m or 15 deg away explains the scan within
  /// ambiguity_residual_m of the winner's residual: the scan cannot tell them apart (seed 000
  /// §4.1: another sector with the same label; or a symmetric room).
  bool ambiguous = false;
  std::string scan_label;
  /// The winner and every pose more than 0.3 m or 15 deg from those before it whose residual
  /// is within ambiguity_residual_m of the winner's: the look-alikes, best first.
  struct Alternative {
    Pose2 pose;
    double residual_m = 0.0;
  };
  std::vector<Alternative> alternatives;
  /// Covariance of (x, y, theta) of `pose`, Gauss-Newton on the readings' distances to their
  /// walls (m^2, m rad, rad^2); infinite where the walls leave a direction free. Zero when
  /// nothing was found.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// Seed 000 §3: the scan's label, matched against every sector's label up to a turn (and up
/// to max_deleted_pairs shallow M m pairs); for each match, the M characters name convex
/// vertices, which the scan locates by fitting lines to the readings on both sides (eqs.
/// (6)-(9)); the pose is the rigid fit of the located vertices to the map's (eqs. (2)-(5)
/// for two, least squares for more). The candidate whose pose lies in its sector and best
/// explains the scan wins. Throws gridloc::Error for a scan that fails validate().
SectorFix localize_in_sectors(const SectorMap& sectors, const RangeScan& scan,
                              const SectorLocalizationOptions& options = {});

}  // namespace gridloc
