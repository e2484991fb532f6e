#pragma once
/// Candidate configurations of one robot (seed 003 ch. III A-B): every placement of a detected
/// feature on the map's corners and walls. A corner gives single poses (eqs. 3.10-3.16 place
/// them; the heading is the turn from the scan's fitted walls to the map's, which eq. 3.27's
/// angle to the corner approximates); a wall gives a segment of poses at the wall's normal
/// offset, the heading fixed by the wall, the position free along it as far as the wall's
/// length allows (ch. III B 1).
#include <Eigen/Core>
#include <vector>

#include "gridloc/engine/team/map_features.hpp"
#include "gridloc/engine/team/scan_features.hpp"
#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// A pose, or a straight segment of poses: pose, then pose moved by t * along for t in
/// [0, length] (same heading). weight: how much the candidate is believed (1 for a feature's
/// placement; the engine's relative score for an estimator's hypothesis).
struct PoseCandidate {
  Pose2 pose;
  Eigen::Vector2d along = Eigen::Vector2d::Zero();  ///< unit, for a segment
  double length = 0.0;                              ///< m; 0 for a single pose
  double weight = 1.0;
  int feature = -1;      ///< index of the scan feature placed (-1: an estimator's hypothesis)
  int map_feature = -1;  ///< index of the map corner or wall it was placed on
  bool segment() const { return length > 0.0; }
  Eigen::Vector2d position(double t = 0.0) const;
};

struct CandidateOptions {
  /// A scan corner is placed on a map corner of the same kind whose free angle differs by
  /// at most this (rad).
  double angle_tolerance = 0.261799387799;  ///< 15 deg
  /// Features placed: the first `features` of the scan's list (corners first, nearest first);
  /// each gives its own placements and a pose that several features give is kept once.
  int features = 1;
  /// Placements closer than these are one (m, rad).
  double merge_m = 0.02;
  double merge_theta = 0.0349065850399;  ///< 2 deg
  /// A single-pose placement is kept when the scan agrees with the map there
  /// (scan_agreement() >= min_agreement); 0 keeps every placement (the thesis's method).
  double min_agreement = 0.8;
  double agreement_tolerance_m = 0.03;  ///< of scan_agreement()
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const CandidateOptions& options);

/// The placements of one feature on the map: a concave or two-wall convex corner on every
/// map corner of its kind and angle (heading from the walls' directions), a one-wall convex
/// corner on every convex map corner along the matching wall, a wall along every map wall
/// long enough for the part seen (the segment of positions where the seen part, between its
/// saturation points, fits on it).
std::vector<PoseCandidate> feature_candidates(const ScanFeature& feature, int feature_index,
                                              const MapFeatures& map,
                                              const CandidateOptions& options = {});

/// A robot's candidates from its scan's features (CandidateOptions::features of them),
/// placements the scan disagrees with removed, duplicates merged.
std::vector<PoseCandidate> robot_candidates(const RangeScan& scan,
                                            const std::vector<ScanFeature>& features,
                                            const MapFeatures& map,
                                            const CandidateOptions& options = {});

/// The share of the scan's readings the map explains at `pose`: a return within tolerance_m
/// of a map wall, a saturated reading whose beam meets no wall closer than max_range -
/// tolerance_m. In [0, 1].
double scan_agreement(const RangeScan& scan, const Pose2& pose, const MapFeatures& map,
                      double tolerance_m);

}  // namespace gridloc
