#pragma once
/// The correlation estimator (seed 001): oriented sonar local grids matched against a
/// contour-thinned global grid by a multiresolution translation x rotation search.
#include <string>
#include <vector>

#include "gridloc/engine/correlation/branch_and_bound.hpp"
#include "gridloc/engine/correlation/search.hpp"
#include "gridloc/engine/estimator.hpp"
#include "gridloc/grids/evidence.hpp"
#include "gridloc/grids/limits.hpp"
#include "gridloc/sensors/range_scan.hpp"
#include "gridloc/sensors/sonar_model.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

/// Exhaustive and BranchAndBound are exact (the same winner, ties to the lowest index);
/// Multires (seed 001 §2) may miss the winner when a coarse level misleads it.
enum class SearchStrategy { Exhaustive, Multires, BranchAndBound };

/// Thresholds of the verdict and scales of the confidence
/// (engine/doc/correlation.md, "Knowing when it is wrong"); the defaults come from the noisy
/// evaluation protocol.
struct VerdictOptions {
  double localized_confidence = 0.20;     ///< below: not localized
  double ambiguity_ratio = 0.97;          ///< a hypothesis scoring this share of the best ...
  double ambiguity_xy = 0.5;              ///< ... farther than this (m) ...
  double ambiguity_theta = 0.5235987756;  ///< ... or turned more than this (rad, 30 deg)
  double distinct_scale = 0.01;           ///< d0 of distinctness d / (d + d0)
  double spread_scale_m = 0.5;            ///< s0 of sharpness exp(-spread / s0)
  /// A winner whose score still rises past the window's edge (Estimate::
  /// rises_past_window_edge: the truth is likely outside the window, a wrong prior) is at
  /// most `not localized`.
  bool rising_edge_not_localized = true;
};

struct CorrelationOptions {
  LocalModel local = LocalModel::Oriented;  ///< oriented (seed 001 §3) or turned (baseline)
  /// thinned (seed 001 §5), raw (baseline) or the likelihood field (issue 13, see `field`)
  GlobalModel global = GlobalModel::Thinned;
  LikelihoodFieldOptions field;  ///< the likelihood field's parameters (checked whatever `global`)
  SearchStrategy strategy = SearchStrategy::BranchAndBound;  ///< the fastest exact one
  ArcRule arc_rule = ArcRule::Neutral;  ///< how arc cells score on free space (see ArcRule)
  SonarModelOptions sonar;              ///< sonar local grid model (arc depth)
  ScanModelOptions scan;                ///< scan local grid model (which cells a beam marks)
  double resolution = 0.1;              ///< finest grid cell = translation step (m)
  int levels = 3;                       ///< multiresolution levels, cells 1x, 2x, 4x ... the finest
  int keep = 8;                         ///< poses kept per level for the next finer one
  int threads = 1;  ///< threads scoring headings / expanding blocks in parallel; same result
  /// A search runs on one thread per this many lattice poses of its window (translations x
  /// headings), at most `threads` and at least one: a small window's second thread costs more
  /// than it shares, and far more with the other core busy (issue 17; bench/RESULTS.md).
  /// 0: every search on `threads`.
  double poses_per_thread = 2e6;
  /// Branch and bound only: stop the search after about this many milliseconds and return
  /// the best pose so far (Estimate::stats says whether it is proven optimal); 0 = no limit.
  double budget_ms = 0.0;
  /// Branch and bound only: bound intervals of headings of a scan, not only single headings
  /// (BranchAndBoundOptions::heading_intervals). Exact either way.
  bool heading_intervals = false;
  /// Branch and bound only: build at most this many levels of the bound pyramid (0: enough
  /// for one block over the whole map). Any depth is exact; a shallow one suits an estimator
  /// that only searches small windows (CoarseToFineEstimator's fine one) and builds faster
  /// in less memory, while a whole-map search on it opens more top blocks.
  int max_bound_depth = 0;
  bool refine = true;  ///< sub-cell refinement of the winner (see refine())
  /// Farthest a local grid may reach (m), for the global grids' padding: 0 means the ring's
  /// reach; set it to a laser's max range to localize scans.
  double reach_m = 0.0;
  /// Distinct poses reported in Estimate::alternatives, the winner included (>= 1): each next
  /// one is the best pose outside the neighbourhoods (distinct_xy, distinct_theta) of those
  /// before it. The second gives second_score and the confidence.
  int hypotheses = 2;
  /// Branch and bound: find the hypotheses after the winner exactly, one search each (each
  /// can cost more than the first: distinct poses score lower, so less is pruned). Off: they
  /// are the best distinct poses the first search happened to score, lower bounds, so
  /// `confidence` is then optimistic (0 when it scored none).
  bool second_peak = true;
  /// The hypotheses after the winner are looked for only among poses scoring at least this
  /// share of it (0: all), by every strategy; branch and bound then finds a scan's in its one
  /// search (BranchAndBoundOptions::keep_share; under a budget, one search each), and a sonar
  /// ring's in one more search each (its flat scores kept most nodes). Below it a second
  /// peak changes no verdict (ambiguity needs VerdictOptions::ambiguity_ratio, 0.97) and little
  /// confidence: the distinctness is then computed with the floor as the second score, a lower
  /// bound (at 0.8 at least 0.952 of what the exact second peak would give), and
  /// Estimate::second_below_floor says so. The search stays exact above the floor.
  double second_peak_floor = 0.8;
  /// Estimate::covariance from the poses within covariance_cells cells and as many heading
  /// steps of the lattice winner (at most (2k+1)^3 extra scores; 0 turns it off).
  int covariance_cells = 3;
  /// ...each weighted by exp((score - best) / covariance_temperature): above 1 a score a few
  /// hits below the best still counts, as it must where the scores' points are not
  /// independent (a laser scan's neighbouring returns on one wall; issue 30: on one-scan maps
  /// the ridge of a corridor then shows in the covariance).
  double covariance_temperature = 1.0;
  /// Estimate::covariance as reported for a sonar ring's readings: the same poses weighted at
  /// this temperature instead (0: covariance_temperature). The verdict's sharpness reads the
  /// spread at covariance_temperature whatever this is (ConfidenceParts::spread_m), so no
  /// verdict changes with it. At 1 the ring's covariance was padded (every `localized` error
  /// within 2 sigma, NEES 0.2-0.4 where 3 is calibrated): fitted on the noisy sonar protocol's
  /// seed 11 and checked on seeds 12 and 13 (README, "How far to trust the covariance").
  double ring_covariance_temperature = 0.15;
  /// A scan's reported covariance keeps this share of the lattice's quantization variance
  /// (step^2 / 12 per axis) when its pose is refined between lattice poses (`refine`): the
  /// refinement may remove part of that error. On the simulated laser half calibrates it (87-91 %
  /// of the `localized` errors within 2 sigma, every one with all of it), but real scans'
  /// global answers are optimistic already (51 % within 2 sigma with all of it, 33 % with
  /// half; README, "How far to trust the covariance"), so all of it is the default. Reported
  /// covariance only (the verdict reads ConfidenceParts::spread_m); a sonar ring keeps all of
  /// it whatever this is.
  double scan_quantization_share = 1.0;
  /// A sonar ring's reported covariance keeps this share of the quantization variance when
  /// its pose is refined (as scan_quantization_share for scans). Reported covariance only.
  /// All of it calibrates the noisy protocol (88 % of the `localized` errors within 2 sigma);
  /// a quiet ring's errors are smaller: with realistic noise 0.25 brings its 98 % to 88-92 %
  /// but leaves the noisy protocol's 78 % (README, "How far to trust the covariance").
  double ring_quantization_share = 1.0;
  /// The reported covariance also spans the window's other peaks (Estimate::alternatives):
  /// its second moment about the winner when each peak carries the winner's spread and the
  /// weight exp((score - best) / T) at the reported temperature. Read around the winner alone
  /// it misses a corridor whose doors make separate peaks along it (issue 30: one-scan maps'
  /// answers slid 0.35-0.63 m along a corridor with a 2-sigma ellipse of 0.2-0.26 m). Reported
  /// covariance only; on for the relations protocol (exhaustive_search()), off elsewhere.
  bool covariance_spans_peaks = false;
  VerdictOptions verdict;
  double distinct_xy = 0.3;                ///< poses farther apart than this (m) ...
  double distinct_theta = 0.261799387799;  ///< ... or this (rad, 15 deg) are distinct
  /// The cells of every global grid (max_cells) and the memory of the grids and of each
  /// search (max_memory_mb, correlation_memory_bytes in memory.hpp) are checked against these
  /// before they are allocated: a fine resolution on a large map is an error, not a crash.
  ResourceLimits limits;
};

/// The bound pyramid depth a search of `window` (at its step_xy) needs: its top blocks cover
/// the window's translations, plus one level (heading intervals widen blocks up to twice
/// their side). A CorrelationEstimator built with this as max_bound_depth answers that
/// window exactly as a deeper one does, and precomputes less (issue 17). At least 1.
int window_bound_depth(const SearchWindow& window);

/// Every lattice pose of a window scored (the exhaustive search's volume): for heatmaps,
/// notebooks and the covariance of the peak. Cell (x, y) of the volume is map grid cell
/// (ix0 + x, iy0 + y) of `geometry` (the finest grid, unpadded); heading index t is heading
/// theta0 + t * step_theta in the grid frame (pose() gives world poses).
struct ScoreVolume {
  int nx = 0, ny = 0, headings = 0;
  int ix0 = 0, iy0 = 0;        ///< the volume's first map cell
  double resolution = 0.0;     ///< m per cell
  double theta0 = 0.0;         ///< grid-frame heading of index 0 (rad)
  double step_theta = 0.0;     ///< rad
  GridGeometry geometry;       ///< the finest grid: resolution, size, origin and yaw
  std::vector<double> scores;  ///< S = sum L * G, at index(x, y, t)
  std::vector<double> mass;    ///< sum |L| of each heading's local grid: the best possible score
  LatticePose best;            ///< the exact winner, in volume indices (ties as every strategy)

  std::size_t index(int x, int y, int t) const {
    return (static_cast<std::size_t>(t) * static_cast<std::size_t>(ny) +
            static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(x);
  }
  double at(int x, int y, int t) const { return scores[index(x, y, t)]; }
  /// World pose of volume coordinates (fractions allowed): the cell's centre, the heading.
  Pose2 pose(double x, double y, double t) const;
};

namespace correlation_detail {
struct PreparedSearch;
}
class PendingEstimate;

class CorrelationEstimator final : public Estimator {
 public:
  /// Precomputes the global grid of every level; throws gridloc::Error for bad options or ring,
  /// and for grids over options.limits (checked before they are allocated).
  CorrelationEstimator(OccupancyMap map, SonarRing ring, CorrelationOptions options = {});
  /// An estimator for scans only (no sonar ring); options.reach_m must cover the scans' range.
  CorrelationEstimator(OccupancyMap map, CorrelationOptions options);

  /// window.step_xy must equal options().resolution (the translation lattice is the grid).
  /// The search's memory (its headings' local grids) is checked against options().limits
  /// before the search (gridloc::Error naming --max-memory-mb).
  Estimate estimate(const Observation& observation, const SearchWindow& window) const override;
  /// The same, reporting up to `hypotheses` distinct poses (>= 1) instead of
  /// options().hypotheses: a global search that seeds a HypothesisSet asks for more.
  Estimate estimate(const Observation& observation, const SearchWindow& window,
                    int hypotheses) const;
  std::string name() const override { return "correlation"; }

  /// The window of a global localization (no prior): the whole map, every heading. The
  /// heading step is the seed's 5 degrees for the sonar ring; for a scan it is the angle
  /// that moves the farthest return by about one cell, acos(1 - res^2 / (2 r^2)), kept
  /// within [0.1, 5] degrees. Search it with SearchStrategy::BranchAndBound: exact, and it
  /// prunes most of the map.
  SearchWindow global_window(const Observation& observation) const;

  /// Scores every lattice pose of `window` (an exhaustive search, whatever the strategy;
  /// same checks and errors as estimate(); the volume's 32 bytes a pose count in its memory).
  ScoreVolume score_volume(const Observation& observation, const SearchWindow& window) const;

  /// The lattice estimate() and score_volume() search for `window`, clipped to the map,
  /// after the same checks of the observation and window (gridloc::Error naming what is
  /// wrong): to size a search before running it.
  Lattice lattice(const Observation& observation, const SearchWindow& window) const;

  const CorrelationOptions& options() const { return options_; }
  const OccupancyMap& map() const { return map_; }
  const SonarRing& ring() const { return ring_; }
  /// The ring an observation's ranges belong to: its own (a fused drive's) or the estimator's.
  const SonarRing& ring_of(const Observation& observation) const {
    return observation.ring ? *observation.ring : ring_;
  }
  /// The padded global grid of level l (0 = finest; the coarser ones exist for the
  /// multiresolution strategy only). Throws std::out_of_range past the last.
  const PaddedGrid& level(int l) const { return levels_.at(static_cast<std::size_t>(l)); }

 private:
  friend class PendingEstimate;
  /// estimate()'s steps before its search (`prepared` gets the lattice, levels and search,
  /// after the checks) and after it (the winner placed, the hypotheses, the covariance and
  /// the verdict, from the search's result).
  void prepare(correlation_detail::PreparedSearch& prepared, const Observation& observation,
               const SearchWindow& window, int hypotheses) const;
  Estimate conclude(correlation_detail::PreparedSearch& prepared, const Observation& observation,
                    const SearchWindow& window) const;
  /// The observation's local grid for heading theta (grid frame) at `resolution`; `points`
  /// are the scan's points under a point model (nullptr otherwise).
  SparseLocalGrid local_grid(const Observation& observation, const ScanPoints* points, double theta,
                             double resolution, const Eigen::Vector2d& centre) const;
  /// The first `count` levels' search levels for `observation`: each padded grid with the
  /// maker of the observation's local grids at its resolution, built on `threads`; `points`
  /// (may be nullptr) on the finest (SearchLevel::points).
  std::vector<SearchLevel> search_levels(const Observation& observation, const ScanPoints* points,
                                         int count, int threads) const;

  OccupancyMap map_;
  SonarRing ring_;
  CorrelationOptions options_;
  double reach_ = 0.0;  ///< what the padding covers (m)
  /// A laser's hits alone: only positive cells, read as fixed point (set in the constructor).
  bool positive_only_ = false;
  /// Whether the padded grids keep their floats beside the int8 cells: for float local grids
  /// (a sonar ring's cones), which read them directly.
  bool keeps_floats() const { return !positive_only_; }
  std::vector<PaddedGrid> levels_;
  BoundPyramid pyramid_;  ///< of levels_[0], built for SearchStrategy::BranchAndBound
};

/// The strategy's short name, as the command line and benchmarks spell it: "bnb",
/// "exhaustive" or "multires".
std::string to_string(SearchStrategy strategy);

/// Checks a window; throws gridloc::Error naming the field.
void validate(const SearchWindow& window);

}  // namespace gridloc
