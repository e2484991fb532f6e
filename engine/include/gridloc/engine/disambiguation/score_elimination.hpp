#pragma once
/// Hypothesis elimination by the engine's own scores (issue 15, beyond seed 002): at a stop,
/// each standing hypothesis predicts where the robot is; the correlation search scores the
/// observation in a small window around each prediction, and the hypotheses scoring far below
/// the best are ruled out — the Localizer's rule (HypothesisSetOptions::drop_ratio), so that
/// noisy sensing and odometry error rule out only what the evidence rules out.
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc {

struct ScoreEliminationOptions {
  double half_xy = 0.3;        ///< m: the window around each predicted pose at the start...
  double half_theta = 0.1745;  ///< rad (10 deg)
  /// ...grown by three standard deviations of the odometry's error over the path driven: this
  /// share of the distance (the Localizer's odometry_error_per_m)...
  double odometry_error_per_m = 0.02;
  /// ...and this heading error per metre (rad/m; 1 deg/m), which also moves the position.
  double odometry_turn_error_per_m = 0.0174532925199;
  double max_half_xy = 2.0;  ///< m: the window grows no larger
  /// A hypothesis scoring below this share of the best is ruled out, in (0, 1] (0.97: seed
  /// 001's ambiguity ratio, as the HypothesisSet uses for sonar).
  double drop_ratio = 0.97;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const ScoreEliminationOptions& options);

/// The window around a prediction after `travelled_m` metres of odometry since the
/// hypotheses' poses were last fixed.
SearchWindow prediction_window(const CorrelationEstimator& estimator,
                               const Observation& observation, const Pose2& predicted,
                               double travelled_m, const ScoreEliminationOptions& options);

/// The windowed search around every predicted pose (world; `travelled_m` driven since the
/// hypotheses were fixed): the engine's score and pose under each hypothesis.
std::vector<Estimate> score_predictions(const CorrelationEstimator& estimator,
                                        const Observation& observation,
                                        const std::vector<Pose2>& predicted, double travelled_m,
                                        const ScoreEliminationOptions& options = {});

/// The indices (ascending) of the scores within `drop_ratio` of the best (a best <= 0 keeps
/// those equal to it). Scores summed over stops serve best: one noisy observation rarely
/// tells look-alikes apart by much, and testing one spot again and again lets noise alone rule
/// the truth out; summed, noise averages out and real differences add up.
std::vector<int> within_drop_ratio(const std::vector<double>& scores, double drop_ratio);

}  // namespace gridloc
