#pragma once
/// What an estimator returns, and where it searches.
#include <limits>
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"

namespace gridloc {

/// The search region around a prior (seed 001 §2: +-80 cm, +-45 deg, 10 cm, 5 deg).
struct SearchWindow {
  Pose2 center;                         ///< the prior, world frame
  double half_xy = 0.8;                 ///< m
  double half_theta = 0.785398163397;   ///< rad (45 deg)
  double step_xy = 0.1;                 ///< m; the finest grid's resolution
  double step_theta = 0.0872664625997;  ///< rad (5 deg)
};

/// A scored pose.
struct Hypothesis {
  Pose2 pose;
  double score = 0.0;
  /// The Localizer's posterior share of this place (its tracked hypotheses' weights sum to
  /// 1); NaN where no tracker weighed it (a single search's alternatives).
  double weight = std::numeric_limits<double>::quiet_NaN();
};

struct SearchStats {
  long long poses_scored = 0;  ///< over all levels
  long long cells_scored = 0;  ///< local cells multiplied, over all levels
  int levels = 1;
  double elapsed_ms = 0.0;  ///< wall time of the whole estimate, grid construction included
  /// True when the lattice winner is proven the best pose of the window (an exact strategy
  /// that ran to the end); false for multires (a heuristic) or a search stopped by its budget.
  bool proven_optimal = true;
  /// No lattice pose of the window scores more than this (= score when proven optimal); NaN
  /// when unknown (multires).
  double upper_bound = 0.0;
};

/// What a navigation stack acts on: drive (localized), ask for help or move to break the
/// symmetry (ambiguous: another place reads the same), relocalize (not localized).
enum class Verdict { Localized, Ambiguous, NotLocalized };

/// "localized", "ambiguous" or "not localized".
std::string to_string(Verdict verdict);

/// The factors of Estimate::confidence, each in [0, 1] (engine/doc/correlation.md, "Knowing when it
/// is wrong").
struct ConfidenceParts {
  double fit = 0.0;           ///< normalized_score clamped: how much of the best possible score
  double agreement = 0.0;     ///< Estimate::agreement (1 for scans, which have none)
  double distinctness = 0.0;  ///< d / (d + 0.01), d = (score - second_score) / score
  double sharpness = 0.0;     ///< exp(-spread_m / 0.5 m)
  /// sqrt(var x + var y) of the winner's covariance at CorrelationOptions::
  /// covariance_temperature (m), which the sharpness reads: Estimate::covariance as reported
  /// may be weighted at another temperature (ring_covariance_temperature).
  double spread_m = 0.0;
};

struct Estimate {
  Pose2 pose;                     ///< best pose after sub-cell refinement, world frame
  Pose2 lattice_pose;             ///< the search's exact winner on the lattice, world frame
  double score = 0.0;             ///< S = sum L * G at lattice_pose (seed 001 eq. 1)
  double normalized_score = 0.0;  ///< score / sum |L|: 1 when every local cell matches fully
  double second_score = 0.0;      ///< best score of a pose distinct from the winner
  /// No distinct pose scores CorrelationOptions::second_peak_floor of the winner or more:
  /// second_score is that floor, an upper bound (so the distinctness is a lower bound).
  bool second_below_floor = false;
  /// In [0, 1]: agreement * fit * distinctness * sharpness (ConfidenceParts).
  double confidence = 0.0;
  ConfidenceParts confidence_parts;
  /// A hypothesis far from the winner (VerdictOptions) scores nearly as much.
  bool ambiguous = false;
  Verdict verdict = Verdict::NotLocalized;
  std::vector<Hypothesis> alternatives;  ///< distinct local maxima, best first (winner included)
  /// The lattice winner lies on the window's edge (x, y or heading; not where the window
  /// was clipped to the map, nor in heading when the window covers every heading): the
  /// best pose may lie outside the window, a sign of a wrong prior.
  bool on_window_edge = false;
  /// On the window's edge, and the poses one and two steps past that edge (on the map) score
  /// above the winner: the score still rises out of the window, so the best pose lies beyond.
  bool rises_past_window_edge = false;
  /// Sonar ring: the share of readings the known map explains at `pose` (a noise-free
  /// simulated reading within 10 cm + 5 % of the measured one, or both no echo). NaN for
  /// scans.
  double agreement = 0.0;
  /// A laser scan's whole-map answer (CoarseToFineEstimator): the share of the scan's returns
  /// whose beam crosses a wall of the map at `pose` (gridloc/sensors/through_walls.hpp); NaN
  /// where it was not checked.
  double through_walls = std::numeric_limits<double>::quiet_NaN();
  /// Covariance of (x, y, theta) in the world frame (m^2, m rad, rad^2), from the scores
  /// around the lattice winner read as a likelihood (examples/gridloc_cli/README.md, under
  /// `localize`; a sonar ring's at CorrelationOptions::ring_covariance_temperature); zero
  /// when not computed (CorrelationOptions::covariance off).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  SearchStats stats;
};

/// Widens `e`'s reported covariance by a floor, floor_m squared on each position variance and
/// floor_rad squared on the heading's: an error the score surface does not see, such as a real
/// map's (LocalizerOptions::reported_floor_m, CoarseToFineOptions::reported_floor_m).
inline void add_reported_floor(Estimate& e, double floor_m, double floor_rad) {
  e.covariance += Eigen::Vector3d(floor_m * floor_m, floor_m * floor_m, floor_rad * floor_rad)
                      .asDiagonal()
                      .toDenseMatrix();
}

}  // namespace gridloc
