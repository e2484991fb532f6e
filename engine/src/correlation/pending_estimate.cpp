// An estimate whose branch-and-bound search runs a budget at a time.
#include "gridloc/engine/correlation/pending_estimate.hpp"

#include <optional>

#include "gridloc/grids/error.hpp"
#include "prepared_search.hpp"

namespace gridloc {

struct PendingEstimate::State {
  explicit State(const CorrelationEstimator& e, const Observation& o, const SearchWindow& w)
      : estimator(e), observation(o), window(w) {}
  const CorrelationEstimator& estimator;
  Observation observation;  ///< the search's levels make its local grids from this copy
  SearchWindow window;
  correlation_detail::PreparedSearch prepared;
  std::unique_ptr<ResumableBranchAndBound> search;  ///< under way
  std::optional<Estimate> estimate;                 ///< once done
};

PendingEstimate::PendingEstimate(const CorrelationEstimator& estimator,
                                 const Observation& observation, const SearchWindow& window,
                                 int hypotheses)
    : state_(std::make_shared<State>(estimator, observation, window)) {
  State& state = *state_;
  if (estimator.options().strategy != SearchStrategy::BranchAndBound) {
    state.estimate = estimator.estimate(state.observation, window, hypotheses);
    return;
  }
  estimator.prepare(state.prepared, state.observation, window, hypotheses);
  correlation_detail::WindowSearch& search = *state.prepared.search;
  search.bnb.heading_intervals = state.prepared.options.heading_intervals;
  search.grids.emplace(search.lattice, search.finest());
  state.search = std::make_unique<ResumableBranchAndBound>(search.lattice, *search.grids,
                                                           search.pyramid, search.bnb);
}

bool PendingEstimate::advance(long long cells) {
  State& state = *state_;
  if (state.estimate) return true;
  if (!state.search->advance(cells)) return false;
  state.prepared.search->result = state.search->take_result();
  state.search.reset();
  state.estimate = state.estimator.conclude(state.prepared, state.observation, state.window);
  state.prepared.search.reset();  // the heading grids: the bulk of its memory
  return true;
}

bool PendingEstimate::done() const {
  return state_->estimate.has_value();
}

double PendingEstimate::open_share() const {
  if (state_->estimate) return 0.0;
  return state_->search->open_share();
}

const Estimate& PendingEstimate::result() const {
  if (!state_->estimate) throw Error("pending estimate: the search is not done yet");
  return *state_->estimate;
}

}  // namespace gridloc
