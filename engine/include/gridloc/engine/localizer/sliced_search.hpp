#pragma once
/// A global search spread over a tracker's updates (issue 34: no stall). A tracker that
/// lost its place re-searches the whole map without stopping its updates: each update
/// advances one exact search by a budget (a PendingEstimate), or runs the next few heading
/// slices (every translation of the map, a slice of the headings, an exact search each, their
/// distinct peaks merged at the end); the answer is taken at the odometry pose of the
/// observation it searched, and the observations taken meanwhile are kept to carry its
/// places up to the latest one.
#include <optional>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/correlation/pending_estimate.hpp"

namespace gridloc {

struct SlicedSearchOptions {
  /// A re-search is cut into heading slices of at most about this many lattice poses
  /// (translations x headings) each; 0: the whole search in one update (a stall). A small
  /// map's search (a sonar ring's room) is one slice, so it answers at once.
  double poses_per_slice = 1.2e6;
  /// A re-search that needs more than one slice instead runs as one branch-and-bound search
  /// of the whole map advanced by about this many local cells or points an update (bounds
  /// and scores, Estimate::stats.cells_scored's unit), its open nodes kept between updates
  /// (PendingEstimate): it costs what one search costs, where the heading slices each
  /// search without the others' best score to prune with. 0: the heading slices.
  double cells_per_update = 4e6;
  int slices_per_update = 1;  ///< slices run per update while a re-search is under way
  /// The distinct peaks each slice reports (each beyond the first costs a search).
  int peaks_per_slice = 2;
  /// A laser's searches run on a coarser copy of the map with cells of this size (m), built
  /// once beside the tracker's; their places are then refined at the tracker's own cell by a
  /// window each. 0 (or the tracker's cell or finer): the tracker's own grids, exact.
  double resolution = 0.2;
  /// A re-search that finishes after the robot drove on carries its places to the latest
  /// observation through up to this many of the observations taken meanwhile, spread along
  /// the path, each matched in the place's window as a tracked place is (the odometry alone
  /// carried them the whole way, and a long way is more than their windows span). 0: the
  /// odometry alone.
  int catch_up_steps = 6;
  /// The first observation's search too (else only re-searches) runs on the coarse copy.
  bool coarse_first_search = true;
  /// A re-search under way is dropped once the tracker's answer is `localized` again on a
  /// single place its last window placed: its places would join with a small share the
  /// track's evidence outweighs (on 81 runs of real buildings every answer was the same
  /// without them), and its slices were most of a lost-then-found track's update time.
  bool drop_once_localized = true;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const SlicedSearchOptions& options);

/// The slices a search of `lattice` is cut into under `options` (>= 1, at most one per
/// heading).
int slice_count(const Lattice& lattice, const SlicedSearchOptions& options);

/// One re-search: the observation it searches, the odometry pose it was taken at, and the
/// slices done so far. A plain value (copied with the tracker's state; the copies of one
/// run a budget at a time share its search).
class SlicedSearch {
 public:
  /// `global` is the estimator's global window for `observation`; `slices` >= 1.
  SlicedSearch(Observation observation, const Pose2& odometry, const SearchWindow& global,
               int slices, int peaks_per_slice);
  /// An observation taken while the search ran, with the odometry pose it was taken at and
  /// the path driven since the search's own (m): its places are carried through some of
  /// them when it finishes (SlicedSearchOptions::catch_up_steps).
  struct PastObservation {
    Pose2 odometry;
    double driven_m = 0.0;
    Observation observation;
  };

  /// The search `pending`, advanced by about `cells_per_update` cells an update (run()'s
  /// `count` times that); its slices are the updates it ran (one more while under way).
  SlicedSearch(Observation observation, const Pose2& odometry, PendingEstimate pending,
               double cells_per_update);

  /// Runs the next `count` slices (fewer when fewer are left).
  void run(const CorrelationEstimator& estimator, int count);
  bool done() const { return pending_ ? pending_->done() : next_ == slices_; }
  int slices_done() const { return next_; }
  int slices() const { return pending_ && !done() ? next_ + 1 : slices_; }
  /// The share of the search done: of its slices, or of its lattice's poses ruled out.
  double progress() const;
  /// Keeps an observation taken while the search runs; beyond 2 `keep` of them every other
  /// one is dropped (the latest stays), so they stay spread along the path.
  void record(PastObservation past, int keep);
  const std::vector<PastObservation>& path() const { return path_; }
  const Observation& observation() const { return observation_; }
  const Pose2& odometry() const { return odometry_; }

  /// The merged answer once done(): the best slice's estimate, its alternatives the distinct
  /// peaks of every slice, best first (poses within `distinct_xy` and `distinct_theta` of a
  /// better one left out), `ambiguous` when the second scores ambiguity_ratio of the first.
  Estimate result(const CorrelationOptions& options) const;

  /// Slice k's window: the whole map, headings [-pi + k w, -pi + (k + 1) w), w = 2 pi / slices.
  SearchWindow slice_window(int k) const;

 private:
  Observation observation_;
  Pose2 odometry_;
  SearchWindow global_;
  int slices_ = 1;
  int peaks_per_slice_ = 1;
  int next_ = 0;
  std::vector<Estimate> found_;             ///< one per slice run
  std::optional<PendingEstimate> pending_;  ///< the search run a budget at a time, if so
  std::vector<PastObservation> path_;       ///< observations taken meanwhile, thinned
  double cells_per_update_ = 0.0;
};

}  // namespace gridloc
