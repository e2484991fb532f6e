#pragma once
/// Hypotheses that survive motion (issue 13): the distinct poses a global search found
/// scoring nearly as much as its winner, carried by odometry, re-scored on each observation
/// in a small window each, merged when they meet and dropped when they fall far below the
/// best. One left: the place is unique; several: look-alikes the drive has not told apart.
#include <Eigen/Core>
#include <vector>

#include "gridloc/engine/estimate.hpp"
#include "gridloc/engine/localizer/held_back.hpp"

namespace gridloc {

struct HypothesisSetOptions {
  /// The most hypotheses tracked (>= 1). A global search asks for one more distinct pose:
  /// when that one still scores within drop_ratio of the winner, more places than the set
  /// holds read the same (HypothesisSet::crowded).
  int max_hypotheses = 4;
  /// A hypothesis scoring less than this share of the best is dropped (in (0, 1]); while
  /// two survive, the answer is `ambiguous`. 0.97: seed 001's ambiguity ratio
  /// (VerdictOptions), calibrated on sonar; real laser logs favour 0.9 (gridloc track
  /// --drop-ratio, README).
  double drop_ratio = 0.97;
  /// Hypotheses closer than these (m, rad) have met: the better one is kept.
  double merge_xy = 0.3;
  double merge_theta = 0.261799387799;  ///< 15 deg
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const HypothesisSetOptions& options);

/// Whether two places lie within merge_xy and merge_theta of each other (they merge).
bool have_met(const Pose2& a, const Pose2& b, const HypothesisSetOptions& options);

/// One tracked pose: where it puts the robot (world frame) at the odometry pose of the
/// latest observation, and that observation's windowed estimate around it.
struct TrackedHypothesis {
  Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double score = 0.0;  ///< the latest observation's score at `pose`
  Estimate estimate;   ///< the search that placed it (its window's own verdict)
  /// The evidence of every observation since it entered (hypothesis_weights.hpp), up to a
  /// constant shared by the set; `weight` is its share of the set's (sums to 1).
  double log_weight = 0.0;
  double weight = 1.0;
  int misses = 0;          ///< observations in a row whose window explained nothing here
  bool confirmed = false;  ///< a window placed it `localized` since it entered
  /// The windows' usual normalized score here (a running mean over the observations that
  /// placed it): an observation scoring far below it is a miss, whatever its verdict.
  double usual_fit = 0.0;
  /// A re-search proposed it (not the first observation's search): it cannot be `localized`
  /// before it has been carried over HypothesisWeightOptions::newcomer_settle_m of driving.
  bool newcomer = false;
  double driven_m = 0.0;  ///< odometry path since it entered
  /// Why the latest observation did not place it `localized` (None when it did).
  HeldBack held_back = HeldBack::None;
};

struct HypothesisSet {
  std::vector<TrackedHypothesis> hypotheses;  ///< best first
  /// A pose outside every hypothesis scored at least this on the seeding search (the next
  /// distinct peak, exact under branch and bound); 0 when the search found no other.
  double elsewhere_score = 0.0;
  bool crowded = false;  ///< elsewhere_score was within drop_ratio of the best at seeding
};

/// The set a global estimate seeds: its alternatives (distinct poses, best first) scoring
/// at least drop_ratio of the winner, up to max_hypotheses; the winner carries the estimate's
/// covariance and pose after refinement, the others their lattice pose and the winner's
/// covariance. `global` must have been asked for max_hypotheses + 1 alternatives.
HypothesisSet seed_hypotheses(const Estimate& global, const HypothesisSetOptions& options);

/// Sorts by score, merges hypotheses that have met (the better one stays), drops those
/// below drop_ratio of the best and keeps at most max_hypotheses.
void merge_and_prune(std::vector<TrackedHypothesis>& hypotheses,
                     const HypothesisSetOptions& options);

/// The estimate the set answers with: the best hypothesis's, its alternatives the set's
/// poses and scores (best first); `ambiguous` (verdict Ambiguous) while more than one
/// hypothesis survives (scores within drop_ratio of the best), else the best's own verdict.
/// Throws gridloc::Error for an empty set.
Estimate set_estimate(const HypothesisSet& set);

}  // namespace gridloc
