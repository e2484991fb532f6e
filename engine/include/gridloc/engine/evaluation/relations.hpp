#pragma once
/// The SLAM benchmark's evaluation of relative motion (Kümmerle et al. 2009) applied to scan
/// matching: for each ground-truth relation between two scans of a log, estimate the motion
/// from the two scans, starting from the logged motion perturbed by seeded noise, and measure
/// the error of the estimate against the relation.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/estimator.hpp"
#include "gridloc/engine/evaluation/calibration.hpp"
#include "gridloc/engine/evaluation/scan_overlap.hpp"
#include "gridloc/engine/icp/robust_icp.hpp"
#include "gridloc/sensors/carmen_log.hpp"
#include "gridloc/sensors/slam_relations.hpp"

namespace gridloc {

/// The correlation options of the relations protocol: CorrelationOptions with the exhaustive
/// strategy, and a covariance from the poses within 5 cells and heading steps of the winner
/// weighted at temperature 10 (CorrelationOptions::covariance_temperature). On one-scan maps a
/// corridor's ridge then shows: over Intel's 106 pairs (5 seeds) and freiburg-079's 1141 (2
/// seeds), correlation + ICP, the 2-sigma ellipse covers 95 % and 94 % of the `localized`
/// answers (87 % and 58 % with 3 cells at temperature 1) and 2 fr079 answers fail while
/// `localized`, against 9 (issue 30). The covariance also spans the window's other peaks
/// (CorrelationOptions::covariance_spans_peaks): Intel's `localized` failures outside their
/// ellipse 21 -> 13 (correlation) and 16 -> 12 (correlation + ICP), fr079's the same.
CorrelationOptions exhaustive_search();

struct RelationEvalOptions {
  /// How a relation's two scans are matched: Icp (match_scans from the prior), Correlation
  /// (the search of the current scan on the reference scan's map) or CorrelationIcp (the
  /// search, then ICP from its winner).
  EstimatorKind matcher = EstimatorKind::Icp;
  std::uint64_t seed = 1;
  /// The prior is the logged motion (the logs hold SLAM-corrected poses, not raw odometry)
  /// plus uniform noise within these bounds on x, y (m) and theta (rad).
  double prior_noise_xy = 0.3;
  double prior_noise_theta = 0.174532925199;  ///< 10 deg
  /// A pair fails when the matcher does not converge or its error exceeds these.
  double failure_xy = 0.2;
  double failure_theta = 0.0872664625997;  ///< 5 deg
  IcpOptions icp;
  /// The correlation matchers: the reference scan becomes a map of this resolution
  /// (scan_occupancy_map, its returns joined into walls), searched with `correlation` (branch and
  /// bound, hits) over a window around the prior covering its noise plus window_margin_xy and
  /// window_margin_theta, in heading steps that move the farthest return by about a cell.
  double map_resolution = 0.05;
  /// The reference scan's map joins its consecutive returns into walls within the adaptive
  /// breakpoint gap (ScanMapOptions: join_returns, join_gap_m, join_grazing_rad).
  bool join_returns = true;
  double join_gap_m = 0.05;
  double join_grazing_rad = 0.174532925199;  ///< 10 deg
  double window_margin_xy = 0.1;
  double window_margin_theta = 0.0349065850399;  ///< 2 deg
  /// The search's options (resolution and reach_m are set per pair). Exhaustive by default:
  /// the same winner as branch and bound on these small windows, without the bound pyramid
  /// that branch and bound builds for a window over the whole padded map (about 10 times the
  /// memory; 1 GB on freiburg-079's 36 m returns).
  CorrelationOptions correlation = exhaustive_search();
  /// A pair whose search grids (the reference scan's padded map and, for branch and bound,
  /// its bound pyramid) would take more than this (MB) is refused with gridloc::Error.
  double max_search_mb = 400.0;
  /// Correlation + ICP: ICP's pose is kept when it converged within these of the search's.
  double refine_max_shift_m = 0.3;
  double refine_max_turn_rad = 0.0872664625997;  ///< 5 deg
  /// Correlation + ICP: ICP also runs from the prior, and its pose wins when it converged
  /// with more fitting pairs (IcpResult::fitting_pairs) than ICP from the search's.
  bool icp_from_prior = false;
  /// A pair's overlap (scan_overlap): the share of the current scan's returns within this of
  /// the reference scan's at the relation's true motion (m).
  double overlap_radius_m = 0.2;
  /// The failure table's overlap bands: [0, e0), [e0, e1), ..., [eN, 1].
  std::vector<double> overlap_band_edges = {0.2, 0.4, 0.6, 0.8};
  /// Pairs overlapping at least this much "overlap" (RelationEvalReport::overlapping): below
  /// it the scans share too little for a match to be asked of them.
  double overlapping_share = 0.5;
};

/// Checks the options; throws gridloc::Error naming the field and its value (negative or
/// non-finite noise, margins or limits, a non-positive resolution, failure threshold or
/// max_search_mb).
void validate(const RelationEvalOptions& options);

/// Mean and standard deviation.
struct ErrorStats {
  double mean = 0.0;
  double std = 0.0;
};

/// One pair's match, as match_relation_pair() gives it.
struct PairMatch {
  Pose2 pose;             ///< the motion of the current scan in the reference's frame
  bool converged = true;  ///< see match_pair()
  /// The correlation matchers: the search's verdict and confidence (nullopt / NaN for Icp).
  std::optional<Verdict> verdict;
  double confidence = std::numeric_limits<double>::quiet_NaN();
  /// Correlation + ICP: ICP's pose was kept (false: the search's).
  bool refined = false;
  std::size_t search_cells = 0;  ///< the padded search grid's cells (0 for Icp)
  /// The answer's covariance in the reference scan's frame: the search's (Correlation and
  /// CorrelationIcp), ICP's Gauss-Newton one (Icp).
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// One relation pair of evaluate_relations().
struct RelationTrial {
  std::size_t pair = 0;       ///< index into the pairs evaluated
  double t1 = 0.0, t2 = 0.0;  ///< the relation's times (s)
  double motion_m = 0.0;      ///< the relation's translation (m) ...
  double motion_deg = 0.0;    ///< ... and |rotation| (deg)
  int returns = 0;            ///< returns of the current scan (at t2)
  Pose2 truth;                ///< the relation's motion (the current scan in the reference's frame)
  Pose2 answer;               ///< the matcher's (PairMatch::pose)
  double translation_error_m = 0.0;
  double rotation_error_deg = 0.0;
  double ms = 0.0;  ///< the match's time, the reference map's construction included
  bool converged = true;
  bool failed = false;
  std::optional<Verdict> verdict;  ///< PairMatch::verdict
  double confidence = std::numeric_limits<double>::quiet_NaN();
  bool refined = false;          ///< PairMatch::refined
  std::size_t search_cells = 0;  ///< PairMatch::search_cells
  double overlap = 0.0;          ///< scan_overlap at the relation's motion
  /// scan_overlap at the answer: far above `overlap` on a failure, the scans fit the answer
  /// better than the relation (a relation off, or a place that repeats).
  double answer_overlap = 0.0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< PairMatch::covariance
  /// The position error lies within the covariance's 2-sigma ellipse
  /// (within_2sigma_ellipse): along a corridor an answer may slide as far as it says.
  bool within_2sigma = false;
};

struct RelationEvalReport {
  int pairs = 0;
  ErrorStats translation_error_m;  ///< |translation of relation^-1 * estimate|, over all pairs
  ErrorStats rotation_error_deg;   ///< |rotation of relation^-1 * estimate|
  int failures = 0;
  int not_converged = 0;   ///< ICP alone: matches that did not converge (counted as failures)
  double median_ms = 0.0;  ///< per match, the reference map's construction included
  std::vector<RelationTrial> trials;  ///< every pair, in the order given
  /// Pairs and failures per overlap band (RelationEvalOptions::overlap_band_edges)...
  std::vector<FailureRow> failures_by_overlap;
  /// ...per verdict of the search ("localized", "ambiguous", "not localized"; "none" for
  /// ICP alone), in that order, rows without pairs left out...
  std::vector<FailureRow> failures_by_verdict;
  /// ...and over the pairs overlapping at least RelationEvalOptions::overlapping_share.
  FailureRow overlapping;
  /// The calibration of the answers a consumer would use: `localized` ones of the search,
  /// converged ones of ICP alone (CalibrationSummary::localized counts them).
  CalibrationSummary calibration;
  /// Of the failures among them, those whose error the 2-sigma ellipse covers: a corridor's
  /// answer that says how far it may slide.
  int covered_failures = 0;
};

/// The motion of `current` in `reference`'s frame by `options.matcher`, from `prior`.
/// `converged`: for Icp, whether ICP converged (false at the iteration limit, with too few
/// pairs, or on a scan ICP cannot use, whose estimate is then the prior); Correlation and
/// CorrelationIcp always answer (true; CorrelationIcp keeps the search's pose when ICP fails).
/// Throws gridloc::Error for a scan that fails validate().
Pose2 match_pair(const RangeScan& reference, const RangeScan& current, const Pose2& prior,
                 const RelationEvalOptions& options, bool* converged = nullptr);

/// match_pair() with the search's verdict, confidence and size. Throws gridloc::Error also
/// for options that fail validate() and for search grids over options.max_search_mb.
PairMatch match_relation_pair(const RangeScan& reference, const RangeScan& current,
                              const Pose2& prior, const RelationEvalOptions& options);

/// Matches every pair by options.matcher (the scan at t1 is the reference) and reports the
/// errors, overall and per pair (RelationEvalReport::trials). Throws gridloc::Error for no
/// pairs, a pair index outside the log, options that fail validate() or a pair whose search
/// would exceed options.max_search_mb (naming the pair and the size).
RelationEvalReport evaluate_relations(const CarmenLog& log, const std::vector<RelationPair>& pairs,
                                      const RelationEvalOptions& options = {});

}  // namespace gridloc
