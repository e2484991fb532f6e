#pragma once
/// Seed 000 §3's localization (Lee, Amato and Fellers): a scan's label matched against the
/// visibility sectors' labels, the matched corners located in the scan and fitted to the
/// map's vertices.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/engine/sectors/scan_label.hpp"
#include "gridloc/engine/sectors/visibility_sectors.hpp"
#include "gridloc/sensors/range_scan.hpp"

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
