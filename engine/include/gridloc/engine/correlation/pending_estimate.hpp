#pragma once
/// An estimate whose search runs a budget at a time (issue 34: a tracker that lost its place
/// searches the whole map again without stalling an update; each update advances the one
/// exact branch-and-bound search by a budget of cells, and it keeps its open nodes for the
/// next). Its answer is CorrelationEstimator::estimate()'s for the same observation, window and
/// hypotheses: the same pose, score, hypotheses, covariance and verdict (only the timing
/// and the counters of the work differ).
#include <memory>

#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc {

class PendingEstimate {
 public:
  /// Starts estimator.estimate(observation, window, hypotheses): the same checks and errors
  /// (gridloc::Error), the local grids made, the top nodes bounded. With the branch-and-bound
  /// strategy its search then runs in advance(); with any other, it runs here, whole. When
  /// the estimator's second_peak_floor is 0 the hypotheses after the winner are searches of
  /// their own, run whole by the advance() that ends the first. The estimator must outlive
  /// it. Copies share the one search.
  PendingEstimate(const CorrelationEstimator& estimator, const Observation& observation,
                  const SearchWindow& window, int hypotheses);

  /// Runs the search on until about `cells` more local cells or points are read (bounds and
  /// scores: Estimate::stats.cells_scored's unit) or it is over, then the steps after it;
  /// true once done.
  bool advance(long long cells);
  bool done() const;
  /// The share of the lattice's poses still in open nodes that could hold the winner: 1 at
  /// the start, 0 once done.
  double open_share() const;
  /// The estimate once done(); gridloc::Error before.
  const Estimate& result() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

}  // namespace gridloc
