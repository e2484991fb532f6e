// The sector protocol: global localization from 360-degree scans on polygon maps, the sector
// estimators and the correlation search on the same trials (sector_protocol.hpp).
#include "gridloc/engine/evaluation/sector_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>

#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/sensors/scan_disturbances.hpp"
#include "seeds.hpp"

namespace gridloc {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double distance_to_walls(const PolygonMap& map, const Eigen::Vector2d& p) {
  const auto edges = polygon_edges(map);
  return distance_to_nearest(p, edges.size(), [&](std::size_t k) {
    return Segment2{edges[k].first, edges[k].second};
  });
}

/// The lowest and the highest corner of the box around `polygon`.
std::pair<Eigen::Vector2d, Eigen::Vector2d> bounding_box(const Polygon& polygon) {
  Eigen::Vector2d lo = polygon.front(), hi = lo;
  for (const auto& p : polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {lo, hi};
}

/// A label a scan cannot pin down: another sector's label turned (Sector::ambiguous), or the
/// label itself turned part of a turn (a rectangle's mMmMmMmM: its sector may hold twin poses).
bool label_ambiguous(const Sector& sector) {
  if (sector.ambiguous) return true;
  const std::string& label = sector.label;
  const std::size_t n = label.size();
  for (std::size_t k = 1; k < n; ++k) {
    if (n % k != 0) continue;
    bool turned_equal = true;
    for (std::size_t i = 0; i < n && turned_equal; ++i) {
      turned_equal = label[i] == label[(i + k) % n];
    }
    if (turned_equal) return true;
  }
  return false;
}

/// Throws gridloc::Error for options the protocol cannot run.
void check(const SectorEvalOptions& options, std::size_t maps) {
  if (options.trials < 1) throw Error("sector evaluation: trials must be >= 1");
  if (maps == 0) throw Error("sector evaluation: no polygon map");
  if (options.estimators.empty()) throw Error("sector evaluation: no estimator");
  for (EstimatorKind kind : options.estimators) {
    if (kind == EstimatorKind::Icp || kind == EstimatorKind::CorrelationIcp) {
      throw Error("sector evaluation: the " + to_string(kind) +
                  " estimator needs a prior; the sector protocol has none (use sectors, "
                  "sectors+correlation or correlation)");
    }
  }
  if (options.beams < 36) {
    throw Error("sector evaluation: beams must be >= 36, got " + std::to_string(options.beams));
  }
  if (!(options.max_range > 0.0) || !std::isfinite(options.max_range)) {
    throw Error("sector evaluation: max_range must be positive, got " +
                std::to_string(options.max_range));
  }
  if (!(options.sigma_m >= 0.0) || !std::isfinite(options.sigma_m)) {
    throw Error("sector evaluation: sigma_m must be >= 0, got " + std::to_string(options.sigma_m));
  }
  if (!(options.clearance_m >= 0.0) || !std::isfinite(options.clearance_m)) {
    throw Error("sector evaluation: clearance_m must be >= 0, got " +
                std::to_string(options.clearance_m));
  }
}

/// True when `kind` is one of the options' estimators.
bool uses(const SectorEvalOptions& options, EstimatorKind kind) {
  return std::count(options.estimators.begin(), options.estimators.end(), kind) > 0;
}

/// The estimators of one map: the sector estimator always (its sector map labels the
/// trials), the others when an estimator of the options needs them.
struct MapEstimators {
  std::shared_ptr<const SectorEstimator> sectors;
  std::shared_ptr<const CorrelationEstimator> correlation;  ///< the global search
  std::unique_ptr<SectorCorrelationEstimator> refined;      ///< sectors+correlation
};

MapEstimators make_estimators(const PolygonMap& polygons, const SectorEvalOptions& options) {
  MapEstimators estimators;
  estimators.sectors = std::make_shared<const SectorEstimator>(polygons, options.sectors);
  if (uses(options, EstimatorKind::Correlation)) {
    CorrelationOptions correlation = options.correlation;
    correlation.reach_m = options.max_range;
    estimators.correlation =
        std::make_shared<const CorrelationEstimator>(rasterize_polygon_map(polygons), correlation);
  }
  if (uses(options, EstimatorKind::SectorsCorrelation)) {
    // The local search runs on its own finer lattice: the sector fix is already within
    // centimetres, and a 10 cm lattice would only blur it.
    CorrelationOptions fine = options.correlation;
    fine.reach_m = options.max_range;
    fine.resolution = options.refinement_resolution;
    auto local = std::make_shared<const CorrelationEstimator>(
        rasterize_polygon_map(polygons, options.refinement_resolution), fine);
    estimators.refined =
        std::make_unique<SectorCorrelationEstimator>(estimators.sectors, local, options.refinement);
  }
  return estimators;
}

/// The whole map as a window; "not localized" answers sit at its centre.
SearchWindow whole_map_window(const PolygonMap& polygons) {
  const auto [lo, hi] = bounding_box(polygons.boundary);
  SearchWindow window;
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  window.center = {c.x(), c.y(), 0.0};
  window.half_xy = 0.5 * (hi - lo).maxCoeff();
  window.half_theta = std::numbers::pi;
  return window;
}

/// Adds the map's sector count and its count of sectors with an ambiguous label to `report`.
void count_sectors(const SectorMap& sector_map, SectorEvalReport& report) {
  int ambiguous_sectors = 0;
  for (const Sector& sector : sector_map.sectors) {
    ambiguous_sectors += label_ambiguous(sector) ? 1 : 0;
  }
  report.sectors_per_map.push_back(static_cast<int>(sector_map.sectors.size()));
  report.ambiguous_sectors_per_map.push_back(ambiguous_sectors);
}

/// What one trial draws; every estimator localizes with the same.
struct SectorTrial {
  Pose2 truth;
  Observation observation;
  int true_sector = -1;
  bool ambiguous_label = false;
  SearchWindow window;
};

/// Trial `t` on the map at index `map_index`: the truth, then the scan's noise seed, drawn
/// from the trial's seed in this order.
SectorTrial draw_trial(const SectorEvalMap& map, std::size_t map_index, int t,
                       const SectorEvalOptions& options, const MapEstimators& estimators,
                       const SearchWindow& whole_map) {
  Rng rng(trial_seed(options.seed, map_index, t));
  SectorTrial trial;
  try {
    trial.truth = sample_polygon_pose(map.polygons, options.clearance_m, rng);
  } catch (const Error& e) {
    throw Error(map.name + ": " + e.what());
  }
  trial.observation.scan =
      polygon_scan(map.polygons, trial.truth, options.beams, options.max_range);
  add_range_noise(*trial.observation.scan, options.sigma_m, rng.next());
  const SectorMap& sector_map = estimators.sectors->sectors();
  trial.true_sector = sector_map.sector_at({trial.truth.x, trial.truth.y});
  trial.ambiguous_label =
      trial.true_sector >= 0 &&
      label_ambiguous(sector_map.sectors[static_cast<std::size_t>(trial.true_sector)]);
  // No prior: the correlation searches the whole map; the sector estimators ignore the
  // window (it only sets on_window_edge).
  trial.window =
      estimators.correlation ? estimators.correlation->global_window(trial.observation) : whole_map;
  return trial;
}

/// The errors and times of one estimator, in run order.
struct EstimatorTally {
  std::vector<double> position_errors;  ///< m
  std::vector<double> heading_errors;   ///< deg
  std::vector<double> ms;
  std::vector<double> success_position_errors;
  std::vector<double> success_heading_errors;
};

/// Localizes trial `t` of map `map_name` with every estimator; tallies and records the
/// outcomes.
void score_trial(const SectorTrial& trial, const std::string& map_name, int t,
                 const MapEstimators& estimators, const SectorEvalOptions& options,
                 std::vector<EstimatorTally>& tallies, SectorEvalReport& report) {
  const Pose2& truth = trial.truth;
  for (std::size_t k = 0; k < tallies.size(); ++k) {
    const EstimatorKind kind = options.estimators[k];
    Estimate estimate;
    int found_sector = -1;
    if (is_sector_estimator(kind)) {
      SectorEstimate located = kind == EstimatorKind::Sectors
                                   ? estimators.sectors->locate(trial.observation, trial.window)
                                   : estimators.refined->locate(trial.observation, trial.window);
      estimate = std::move(located.estimate);
      found_sector = located.fix.found ? located.fix.sector : -1;
    } else {
      estimate = estimators.correlation->estimate(trial.observation, trial.window);
      found_sector = estimators.sectors->sectors().sector_at({estimate.pose.x, estimate.pose.y});
    }
    const double position_error = std::hypot(estimate.pose.x - truth.x, estimate.pose.y - truth.y);
    const double heading_error = std::abs(normalize_angle(estimate.pose.theta - truth.theta));
    // "Not localized" answers sit at the window's centre: never a success, wherever that is.
    const bool success = position_error <= options.success_xy &&
                         heading_error <= options.success_theta &&
                         estimate.verdict != Verdict::NotLocalized;
    EstimatorTally& tally = tallies[k];
    tally.position_errors.push_back(position_error);
    tally.heading_errors.push_back(rad2deg(heading_error));
    tally.ms.push_back(estimate.stats.elapsed_ms);
    if (success) {
      tally.success_position_errors.push_back(position_error);
      tally.success_heading_errors.push_back(rad2deg(heading_error));
    }
    report.records.push_back({map_name, t, k, truth, trial.true_sector, found_sector,
                              trial.ambiguous_label, success, position_error,
                              rad2deg(heading_error), std::move(estimate)});
  }
}

/// Adds estimator `k`'s successes, identified sectors, verdicts and ambiguity answers over
/// `records` to `result`.
void count_outcomes(const std::vector<SectorTrialRecord>& records, std::size_t k,
                    SectorEvalResult& result) {
  for (const SectorTrialRecord& record : records) {
    if (record.estimator != k) continue;
    const Verdict v = record.estimate.verdict;
    result.successes += record.success ? 1 : 0;
    result.sector_identified +=
        record.true_sector >= 0 && record.found_sector == record.true_sector ? 1 : 0;
    result.localized += v == Verdict::Localized ? 1 : 0;
    result.ambiguous += v == Verdict::Ambiguous ? 1 : 0;
    result.not_localized += v == Verdict::NotLocalized ? 1 : 0;
    result.false_fixes += !record.success && v == Verdict::Localized ? 1 : 0;
    if (record.ambiguous_label) {
      ++result.ambiguous_label_trials;
      result.ambiguity_detected += v == Verdict::Ambiguous ? 1 : 0;
      result.ambiguity_answered_wrongly += !record.success && v == Verdict::Localized ? 1 : 0;
    }
  }
}

/// Estimator `k`'s result over all `total` trials.
SectorEvalResult summarize(const SectorEvalOptions& options, std::size_t k, int total,
                           const EstimatorTally& tally,
                           const std::vector<SectorTrialRecord>& records) {
  SectorEvalResult result;
  result.estimator = options.estimators[k];
  result.trials = total;
  count_outcomes(records, k, result);
  result.success_rate = static_cast<double>(result.successes) / total;
  result.sector_identification_rate = static_cast<double>(result.sector_identified) / total;
  for (double v : tally.position_errors) result.mean_position_error_m += v / total;
  for (double v : tally.heading_errors) result.mean_heading_error_deg += v / total;
  result.median_position_error_m = median(tally.success_position_errors);
  result.median_heading_error_deg = median(tally.success_heading_errors);
  result.median_ms = median(tally.ms);
  const int answered = result.ambiguity_detected + result.ambiguity_answered_wrongly;
  result.ambiguity_detection_rate = answered > 0
                                        ? static_cast<double>(result.ambiguity_detected) / answered
                                        : std::numeric_limits<double>::quiet_NaN();
  return result;
}

}  // namespace

Pose2 sample_polygon_pose(const PolygonMap& map, double clearance, Rng& rng) {
  const auto [lo, hi] = bounding_box(map.boundary);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Eigen::Vector2d p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
    const double theta = rng.uniform(-std::numbers::pi, std::numbers::pi);
    if (!inside(map.boundary, p)) continue;
    if (std::any_of(map.obstacles.begin(), map.obstacles.end(),
                    [&](const Polygon& obstacle) { return inside(obstacle, p); })) {
      continue;
    }
    if (distance_to_walls(map, p) < clearance) continue;
    return {p.x(), p.y(), theta};
  }
  throw Error("sector evaluation: found no pose " + std::to_string(clearance) +
              " m from every wall of this polygon map");
}

SectorEvalReport run_sector_evaluation(const std::vector<SectorEvalMap>& maps,
                                       const SectorEvalOptions& options,
                                       const std::function<void(int, int)>& progress) {
  check(options, maps.size());
  std::vector<EstimatorTally> tallies(options.estimators.size());
  const int total = options.trials * static_cast<int>(maps.size());
  int done = 0;
  SectorEvalReport report;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const MapEstimators estimators = make_estimators(maps[m].polygons, options);
    const SearchWindow whole_map = whole_map_window(maps[m].polygons);
    count_sectors(estimators.sectors->sectors(), report);
    for (int t = 0; t < options.trials; ++t) {
      const SectorTrial trial = draw_trial(maps[m], m, t, options, estimators, whole_map);
      score_trial(trial, maps[m].name, t, estimators, options, tallies, report);
      if (progress) progress(++done, total);
    }
  }
  report.trials = total;
  for (std::size_t k = 0; k < tallies.size(); ++k) {
    report.results.push_back(summarize(options, k, total, tallies[k], report.records));
  }
  return report;
}

}  // namespace gridloc
