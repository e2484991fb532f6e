#pragma once
// What one CorrelationEstimator::estimate() searches, shared by estimator.cpp and the pending
// estimate that runs the same search a budget at a time (pending_estimate.cpp).
#include <chrono>
#include <optional>
#include <vector>

#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/engine/correlation/estimator.hpp"

namespace gridloc::correlation_detail {

/// One estimate()'s search of its lattice, shared by the steps after it: the levels searched,
/// the branch-and-bound heading grids (made by the first search, reused by the next
/// hypotheses, the refinement and the covariance) and options, and what the searches found.
struct WindowSearch {
  WindowSearch(const Lattice& searched, const std::vector<SearchLevel>& search_levels,
               const BoundPyramid& bound_pyramid)
      : lattice(searched), levels(search_levels), pyramid(bound_pyramid) {}
  const SearchLevel& finest() const { return levels.front(); }

  const Lattice& lattice;
  const std::vector<SearchLevel>& levels;
  const BoundPyramid& pyramid;        ///< of the finest level's grid (branch and bound)
  std::optional<HeadingGrids> grids;  ///< branch and bound only
  BranchAndBoundOptions bnb;
  SearchResult result;  ///< of the first search, with the counters of all
};

/// What one estimate() searches, and the search: the options with its hypotheses and
/// threads, the lattice, the observation's points and levels (not movable: the levels point
/// at the points, the search at both).
struct PreparedSearch {
  PreparedSearch() = default;
  PreparedSearch(const PreparedSearch&) = delete;
  PreparedSearch& operator=(const PreparedSearch&) = delete;

  CorrelationOptions options;
  Lattice lattice;
  std::optional<ScanPoints> points;
  int level_count = 1;
  std::vector<SearchLevel> levels;
  std::optional<WindowSearch> search;
  std::chrono::steady_clock::time_point start;
};

}  // namespace gridloc::correlation_detail
