#include "gridloc/engine/team/estimate_candidates.hpp"

#include <cmath>

#include "gridloc/grids/error.hpp"

namespace gridloc {

void validate(const EstimateCandidateOptions& options) {
  if (!(options.min_score_ratio > 0.0 && options.min_score_ratio <= 1.0))
    throw Error("min_score_ratio must be in (0, 1]");
  if (options.max_candidates < 1) throw Error("max_candidates must be >= 1");
}

std::vector<PoseCandidate> estimate_candidates(const Estimate& estimate,
                                               const EstimateCandidateOptions& options) {
  validate(options);
  if (options.skip_not_localized && estimate.verdict == Verdict::NotLocalized) return {};
  std::vector<Hypothesis> hypotheses = estimate.alternatives;
  if (hypotheses.empty()) hypotheses.push_back({estimate.lattice_pose, estimate.score});
  const double best = hypotheses.front().score;
  std::vector<PoseCandidate> candidates;
  if (!(best > 0.0)) return candidates;
  for (std::size_t k = 0; k < hypotheses.size(); ++k) {
    const double ratio = hypotheses[k].score / best;
    if (ratio < options.min_score_ratio) continue;
    if (static_cast<int>(candidates.size()) >= options.max_candidates) return {};  // crowded
    PoseCandidate candidate;
    candidate.pose = k == 0 ? estimate.pose : hypotheses[k].pose;
    candidate.weight = ratio;
    candidates.push_back(candidate);
  }
  return candidates;
}

}  // namespace gridloc
