#pragma once
/// The sector protocol (issue 6; `gridloc eval` on polygon maps): global localization, no
/// prior, from one 360-degree scan with range noise, taken at random poses of a polygon map.
/// Every estimator sees the same poses and scans, so the visibility sectors of seed 000 and the
/// correlation search of seed 001 compare trial for trial.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gridloc/engine/correlation/estimator.hpp"
#include "gridloc/engine/sectors/estimator.hpp"
#include "gridloc/grids/polygon_map.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

struct SectorEvalOptions {
  int trials = 100;  ///< per map
  std::uint64_t seed = 1;
  int beams = 360;           ///< per scan, evenly over 360 deg
  double max_range = 8.0;    ///< m; beyond it a beam has no return
  double sigma_m = 0.01;     ///< Gaussian range noise (m)
  double clearance_m = 0.3;  ///< true poses lie at least this far from every wall (m)
  double success_xy = 0.10;  ///< seed 001's success: position error at most this (m) ...
  double success_theta = 0.122173047640;  ///< ... and heading error at most 7 deg
  /// Any of sectors, sectors+correlation and correlation (global search, exact bnb).
  std::vector<EstimatorKind> estimators = {EstimatorKind::Sectors, EstimatorKind::Correlation};
  SectorEstimatorOptions sectors;
  SectorCorrelationOptions refinement;  ///< of sectors+correlation
  /// The lattice (and rasterization) of sectors+correlation's local search (m).
  double refinement_resolution = kSectorRefinementResolution;
  /// The correlation's options; reach_m is set to max_range. Its map is the polygon map
  /// rasterized at the map's own resolution.
  CorrelationOptions correlation;
};

struct SectorEvalMap {
  std::string name;
  PolygonMap polygons;
};

/// One estimator's results over every trial of every map.
struct SectorEvalResult {
  EstimatorKind estimator = EstimatorKind::Sectors;
  int trials = 0;
  int successes = 0;
  double success_rate = 0.0;
  /// Trials whose estimate names the true sector: the sector the label matched (sectors,
  /// sectors+correlation), or the sector the pose lies in (correlation).
  int sector_identified = 0;
  double sector_identification_rate = 0.0;
  double mean_position_error_m = 0.0;    ///< over all trials, failures included
  double mean_heading_error_deg = 0.0;   ///< over all trials
  double median_position_error_m = 0.0;  ///< over the successes (NaN without one)
  double median_heading_error_deg = 0.0;
  double median_ms = 0.0;  ///< estimate() wall time
  int localized = 0;       ///< verdict "localized"
  int ambiguous = 0;       ///< verdict "ambiguous"
  int not_localized = 0;   ///< verdict "not localized"
  /// Failures reported as "localized": a wrong pose given as a fix, the worst outcome.
  int false_fixes = 0;
  /// Trials whose true sector's label another sector shares up to a turn (seed 000 §4.1), or
  /// equals itself turned part of a turn (a rectangle's): the look-alikes the labels show. A
  /// look-alike whose sector's label came out otherwise is not counted.
  int ambiguous_label_trials = 0;
  /// Of those: answered "ambiguous" (detected), or a failure answered "localized" (answered
  /// wrongly); the rest are successes or "not localized".
  int ambiguity_detected = 0;
  int ambiguity_answered_wrongly = 0;
  /// detected / (detected + answered wrongly); NaN when neither happened.
  double ambiguity_detection_rate = 0.0;
};

/// One trial of one estimator (`gridloc eval --trials-out`).
struct SectorTrialRecord {
  std::string map;
  int trial = 0;
  std::size_t estimator = 0;  ///< index into SectorEvalOptions::estimators
  Pose2 truth;
  int true_sector = -1;
  int found_sector = -1;
  bool ambiguous_label = false;
  bool success = false;  ///< within success_xy and success_theta, and not "not localized"
  double position_error_m = 0.0;
  double heading_error_deg = 0.0;
  Estimate estimate;
};

struct SectorEvalReport {
  int trials = 0;                         ///< over all maps
  std::vector<SectorEvalResult> results;  ///< one per estimator, in options order
  std::vector<SectorTrialRecord> records;
  std::vector<int> sectors_per_map;            ///< sector count of each map
  std::vector<int> ambiguous_sectors_per_map;  ///< sectors with a shared or periodic label
};

/// A pose drawn uniformly in the free space of `map`, at least `clearance` from every edge,
/// heading uniform. Throws gridloc::Error when none is found in many attempts.
Pose2 sample_polygon_pose(const PolygonMap& map, double clearance, Rng& rng);

/// Runs the protocol. `progress(done, total)` after every trial. Throws gridloc::Error for
/// bad options (no trial, no map, no estimator, an ICP estimator, bad scan settings).
SectorEvalReport run_sector_evaluation(const std::vector<SectorEvalMap>& maps,
                                       const SectorEvalOptions& options,
                                       const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
