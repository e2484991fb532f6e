#pragma once
/// Team localization on top of any estimator (beyond seed 003): a robot's candidates are the
/// distinct poses its own estimate found (the correlation search's top-k local maxima, the
/// sector estimator's look-alikes), weighted by their scores, so a sonar ring or a laser
/// takes the IR sensor's place and the team solver picks the consistent assignment of
/// highest total score.
#include <vector>

#include "gridloc/engine/estimate.hpp"
#include "gridloc/engine/team/pose_candidates.hpp"

namespace gridloc {

struct EstimateCandidateOptions {
  /// Alternatives scoring below this share of the winner are left out (in (0, 1]).
  double min_score_ratio = 0.8;
  int max_candidates = 8;  ///< at most this many, best first (>= 1)
  /// An estimate whose own verdict is `not localized` (its best pose scores too little to be
  /// believed, e.g. a sonar ring against walls it cannot see) gives no candidate: the robot
  /// is then placed by its links alone, instead of lending a wrong pose to the team.
  bool skip_not_localized = true;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const EstimateCandidateOptions& options);

/// The estimate's alternatives (its refined pose for the winner) as candidates of weight
/// score / winner's score. Empty when the estimate has no positive score, is `not localized`
/// with skip_not_localized, or is crowded: more than max_candidates alternatives score at
/// least min_score_ratio (the estimate should be asked for max_candidates + 1), so the truth
/// may be among those left out and any team answer built on the list could be wrong.
std::vector<PoseCandidate> estimate_candidates(const Estimate& estimate,
                                               const EstimateCandidateOptions& options = {});

}  // namespace gridloc
