#pragma once
/// The scan side of team localization (seed 003 ch. III A-B, ch. VI B): the corners, walls and
/// saturation points in one robot's short-range scan, found by least-squares wall fits and
/// the fitted walls' intersection, and the Cartesian offsets from each.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/sensors/range_scan.hpp"

namespace gridloc {

enum class FeatureKind {
  ConcaveCorner,        ///< two walls meeting, the free space turning left (eqs. 3.1-3.16)
  ConvexCorner,         ///< two walls seen meeting, turning right (eqs. 3.1-3.16)
  ConvexCornerOneWall,  ///< one wall ending in a corner that hides the other (eqs. 3.17-3.24)
  Wall,                 ///< a wall between two saturation points (eqs. 3.31-3.35)
};

/// "concave corner", "convex corner", "convex corner (one wall)", "wall".
std::string to_string(FeatureKind kind);

/// A feature in the robot (scan) frame, m. Walls run the way the scan does (counter-clockwise
/// around the robot, so the robot is on their left, as the map's walls have the free space on
/// theirs).
struct ScanFeature {
  FeatureKind kind = FeatureKind::Wall;
  /// Corners: the corner (the fitted walls' intersection; for a one-wall corner the seen
  /// wall's return next to the jump, projected on its fitted line). Wall: the foot of the
  /// perpendicular from the robot on the wall's fitted line.
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  /// Unit directions of the walls: wall1 arrives at the corner, wall2 leaves it. A wall or a
  /// one-wall corner has only wall1 (wall2 zero).
  Eigen::Vector2d wall1 = Eigen::Vector2d::Zero(), wall2 = Eigen::Vector2d::Zero();
  /// ConvexCornerOneWall: true when the seen wall arrives at the corner (it is before the
  /// corner in scan order, eq. 3.24), false when it leaves it (eq. 3.18).
  bool seen_wall_arrives = false;
  /// Where the feature's walls end in the scan (saturation points or the last point of a
  /// wall): first before the feature in scan order, second after; the first and last returns
  /// of its walls, projected on their fitted lines.
  Eigen::Vector2d saturation1 = Eigen::Vector2d::Zero(), saturation2 = Eigen::Vector2d::Zero();
  /// Two-wall corners: the interior angle on the robot's side (rad; concave < pi < convex);
  /// 0 for a one-wall corner (its hidden wall's direction is unknown) and a wall.
  double free_angle = 0.0;
  double fit_rms_m = 0.0;  ///< rms distance of the fitted points from their walls
  int points = 0;          ///< scan points the feature's walls were fitted to
};

struct FeatureOptions {
  /// A run of returns is split where a point lies farther than this from the line through
  /// the run's ends (m; split-and-merge), and adjacent pieces whose joint fit stays within it
  /// are merged back.
  double split_m = 0.012;
  /// Returns farther apart than this (m) belong to different runs (a jump: an occlusion).
  double gap_m = 0.05;
  int min_wall_points = 6;           ///< a fitted wall needs at least this many returns
  double min_wall_m = 0.04;          ///< and at least this length (m)
  double min_turn = 0.349065850399;  ///< 20 deg: two fitted walls meeting at less turn are one
  /// A run's end within this of the scan's max range is a saturation point, not a corner (m);
  /// so is an end next to a saturated beam that the wall's fitted line, had the wall gone on,
  /// would meet no nearer than this below the max range (a wall at a glancing angle running
  /// out of range).
  double saturation_margin_m = 0.015;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const FeatureOptions& options);

/// The features of a scan, corners first (ConcaveCorner, ConvexCorner, ConvexCornerOneWall,
/// then Wall), each kind nearest first (equally near ones in scan order). Readings at or above
/// scan.max_range are no return. Empty when the scan holds no wall (e.g. every reading
/// saturated). A run's end is a one-wall convex corner when it is no saturation point and the
/// neighbouring reading jumps farther (or reads nothing) than where the wall, had it gone on,
/// would have met that beam (by split_m); a jump nearer is something in front of the wall,
/// no corner of it. Throws gridloc::Error naming the field for options validate() refuses,
/// and for a scan validate() refuses for any reason but having no return.
std::vector<ScanFeature> extract_features(const RangeScan& scan,
                                          const FeatureOptions& options = {});

/// Seed 003's offsets of the robot from a feature's walls in the scan frame: offset1 along
/// wall1's normal, offset2 along wall2's normal for corners with two walls (eqs. 3.8-3.9),
/// along the seen wall's normal and along the wall for a one-wall corner (eqs. 3.20-3.21), and
/// the normal offset alone (offset2 zero) for a wall (eq. 3.33). The normals are the walls
/// turned by +90 deg ([0 0 1] x wall, eqs. 3.6-3.7), so offset1 is the vector from the robot
/// to the foot of its perpendicular on wall1's line.
struct FeatureOffsets {
  Eigen::Vector2d offset1 = Eigen::Vector2d::Zero(), offset2 = Eigen::Vector2d::Zero();
};
/// The feature's offsets (m, scan frame). The walls are normalized; throws gridloc::Error for
/// a wall that is zero or not finite.
FeatureOffsets feature_offsets(const ScanFeature& feature);

/// The Cartesian offsets (dx, dy) from the robot to the feature's point in the map frame,
/// once the feature's walls are matched to map walls of unit directions env_wall1, env_wall2
/// (eqs. 3.10-3.16: T = A_scan^-1 A_env applied to the offsets); for a one-wall corner or a
/// wall env_wall2 is ignored (the normal is formed as eqs. 3.19, 3.32). For walls that are not
/// perpendicular the transformed offsets are not summed (eqs. 3.15-3.16 hold for right angles
/// only): the corner is the point at the transformed normals' offsets, the sum again at right
/// angles. With exact data (env walls = the scan's walls rotated by the robot's heading) the
/// result is the map-frame vector from the robot to the corner, or to the foot on a wall (m).
/// The directions are normalized; throws gridloc::Error for a zero or non-finite one, or for
/// parallel walls (the feature's or the map's).
Eigen::Vector2d cartesian_offsets(const ScanFeature& feature, const Eigen::Vector2d& env_wall1,
                                  const Eigen::Vector2d& env_wall2);

}  // namespace gridloc
