// The sector protocol: global localization from 360-degree scans on polygon maps, the sector
// estimators and the correlation search on the same trials (sector_protocol.hpp).
#include "gridloc/engine/evaluation/sector_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/scan_disturbances.hpp"

namespace gridloc {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  return Rng(a * 0x100000001B3ull ^ b).next();
}

double distance_to_walls(const PolygonMap& map, const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : polygon_edges(map)) {
    const Eigen::Vector2d e = b - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * e - p).norm());
  }
  return d;
}

/// A label a scan cannot pin down: another sector's label turned (Sector::ambiguous), or the
/// label itself turned part of a turn (a rectangle's mMmMmMmM: its sector may hold twin poses).
bool label_ambiguous(const Sector& s) {
  if (s.ambiguous) return true;
  const std::string& l = s.label;
  const std::size_t n = l.size();
  for (std::size_t k = 1; k < n; ++k) {
    if (n % k != 0) continue;
    bool turned_equal = true;
    for (std::size_t i = 0; i < n && turned_equal; ++i) turned_equal = l[i] == l[(i + k) % n];
    if (turned_equal) return true;
  }
  return false;
}

void check(const SectorEvalOptions& o, std::size_t maps) {
  if (o.trials < 1) throw Error("sector evaluation: trials must be >= 1");
  if (maps == 0) throw Error("sector evaluation: no polygon map");
  if (o.estimators.empty()) throw Error("sector evaluation: no estimator");
  for (EstimatorKind k : o.estimators) {
    if (k == EstimatorKind::Icp || k == EstimatorKind::CorrelationIcp) {
      throw Error("sector evaluation: the " + to_string(k) +
                  " estimator needs a prior; the sector protocol has none (use sectors, "
                  "sectors+correlation or correlation)");
    }
  }
  if (o.beams < 36) {
    throw Error("sector evaluation: beams must be >= 36, got " + std::to_string(o.beams));
  }
  if (!(o.max_range > 0.0) || !std::isfinite(o.max_range)) {
    throw Error("sector evaluation: max_range must be positive, got " +
                std::to_string(o.max_range));
  }
  if (!(o.sigma_m >= 0.0) || !std::isfinite(o.sigma_m)) {
    throw Error("sector evaluation: sigma_m must be >= 0, got " + std::to_string(o.sigma_m));
  }
  if (!(o.clearance_m >= 0.0) || !std::isfinite(o.clearance_m)) {
    throw Error("sector evaluation: clearance_m must be >= 0, got " +
                std::to_string(o.clearance_m));
  }
}

}  // namespace

Pose2 sample_polygon_pose(const PolygonMap& map, double clearance, Rng& rng) {
  Eigen::Vector2d lo = map.boundary.front(), hi = lo;
  for (const auto& p : map.boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Eigen::Vector2d p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
    const double theta = rng.uniform(-std::numbers::pi, std::numbers::pi);
    if (!inside(map.boundary, p)) continue;
    if (std::any_of(map.obstacles.begin(), map.obstacles.end(),
                    [&](const Polygon& o) { return inside(o, p); })) {
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
  const std::size_t ne = options.estimators.size();
  const bool need_correlation = std::count(options.estimators.begin(), options.estimators.end(),
                                           EstimatorKind::Correlation) > 0;
  std::vector<std::vector<double>> pos_err(ne), head_err(ne), ms(ne), good_pos(ne), good_head(ne);
  const int total = options.trials * static_cast<int>(maps.size());
  int done = 0;
  SectorEvalReport report;

  for (std::size_t m = 0; m < maps.size(); ++m) {
    const PolygonMap& polygons = maps[m].polygons;
    auto sectors = std::make_shared<const SectorEstimator>(polygons, options.sectors);
    std::shared_ptr<const CorrelationEstimator> correlation;
    if (need_correlation) {
      CorrelationOptions c = options.correlation;
      c.reach_m = options.max_range;
      correlation =
          std::make_shared<const CorrelationEstimator>(rasterize_polygon_map(polygons), c);
    }
    std::unique_ptr<SectorCorrelationEstimator> refined;
    if (std::count(options.estimators.begin(), options.estimators.end(),
                   EstimatorKind::SectorsCorrelation) > 0) {
      // The local search runs on its own finer lattice: the sector fix is already within
      // centimetres, and a 10 cm lattice would only blur it.
      CorrelationOptions fine = options.correlation;
      fine.reach_m = options.max_range;
      fine.resolution = options.refinement_resolution;
      auto local = std::make_shared<const CorrelationEstimator>(
          rasterize_polygon_map(polygons, options.refinement_resolution), fine);
      refined = std::make_unique<SectorCorrelationEstimator>(sectors, local, options.refinement);
    }
    const SectorMap& sm = sectors->sectors();
    Eigen::Vector2d lo = polygons.boundary.front(), hi = lo;
    for (const auto& p : polygons.boundary) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    int ambiguous_sectors = 0;
    for (const Sector& s : sm.sectors) ambiguous_sectors += label_ambiguous(s) ? 1 : 0;
    report.sectors_per_map.push_back(static_cast<int>(sm.sectors.size()));
    report.ambiguous_sectors_per_map.push_back(ambiguous_sectors);

    for (int t = 0; t < options.trials; ++t) {
      Rng rng(mix(mix(options.seed, m), static_cast<std::uint64_t>(t)));
      Pose2 truth;
      try {
        truth = sample_polygon_pose(polygons, options.clearance_m, rng);
      } catch (const Error& e) {
        throw Error(maps[m].name + ": " + e.what());
      }
      Observation obs;
      obs.scan = polygon_scan(polygons, truth, options.beams, options.max_range);
      add_range_noise(*obs.scan, options.sigma_m, rng.next());
      const int true_sector = sm.sector_at({truth.x, truth.y});
      const bool ambiguous_label =
          true_sector >= 0 && label_ambiguous(sm.sectors[static_cast<std::size_t>(true_sector)]);
      // No prior: the correlation searches the whole map; the sector estimators ignore the
      // window (it only sets on_window_edge).
      SearchWindow window;
      if (correlation) {
        window = correlation->global_window(obs);
      } else {  // the whole map; "not localized" answers sit at its centre
        const Eigen::Vector2d c = 0.5 * (lo + hi);
        window.center = {c.x(), c.y(), 0.0};
        window.half_xy = 0.5 * (hi - lo).maxCoeff();
        window.half_theta = std::numbers::pi;
      }
      for (std::size_t k = 0; k < ne; ++k) {
        const EstimatorKind kind = options.estimators[k];
        Estimate e;
        int found_sector = -1;
        if (is_sector_estimator(kind)) {
          SectorEstimate se = kind == EstimatorKind::Sectors ? sectors->locate(obs, window)
                                                             : refined->locate(obs, window);
          e = std::move(se.estimate);
          found_sector = se.fix.found ? se.fix.sector : -1;
        } else {
          e = correlation->estimate(obs, window);
          found_sector = sm.sector_at({e.pose.x, e.pose.y});
        }
        const double dp = std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
        const double dt = std::abs(normalize_angle(e.pose.theta - truth.theta));
        // "Not localized" answers sit at the window's centre: never a success, wherever that is.
        const bool success = dp <= options.success_xy && dt <= options.success_theta &&
                             e.verdict != Verdict::NotLocalized;
        pos_err[k].push_back(dp);
        head_err[k].push_back(rad2deg(dt));
        ms[k].push_back(e.stats.elapsed_ms);
        if (success) good_pos[k].push_back(dp), good_head[k].push_back(rad2deg(dt));
        report.records.push_back({maps[m].name, t, k, truth, true_sector, found_sector,
                                  ambiguous_label, success, dp, rad2deg(dt), std::move(e)});
      }
      if (progress) progress(++done, total);
    }
  }

  report.trials = total;
  for (std::size_t k = 0; k < ne; ++k) {
    SectorEvalResult r;
    r.estimator = options.estimators[k];
    r.trials = total;
    for (const SectorTrialRecord& rec : report.records) {
      if (rec.estimator != k) continue;
      const Verdict v = rec.estimate.verdict;
      r.successes += rec.success ? 1 : 0;
      r.sector_identified += rec.true_sector >= 0 && rec.found_sector == rec.true_sector ? 1 : 0;
      r.localized += v == Verdict::Localized ? 1 : 0;
      r.ambiguous += v == Verdict::Ambiguous ? 1 : 0;
      r.not_localized += v == Verdict::NotLocalized ? 1 : 0;
      r.false_fixes += !rec.success && v == Verdict::Localized ? 1 : 0;
      if (rec.ambiguous_label) {
        ++r.ambiguous_label_trials;
        r.ambiguity_detected += v == Verdict::Ambiguous ? 1 : 0;
        r.ambiguity_answered_wrongly += !rec.success && v == Verdict::Localized ? 1 : 0;
      }
    }
    r.success_rate = static_cast<double>(r.successes) / total;
    r.sector_identification_rate = static_cast<double>(r.sector_identified) / total;
    for (double v : pos_err[k]) r.mean_position_error_m += v / total;
    for (double v : head_err[k]) r.mean_heading_error_deg += v / total;
    r.median_position_error_m = median(good_pos[k]);
    r.median_heading_error_deg = median(good_head[k]);
    r.median_ms = median(ms[k]);
    const int answered = r.ambiguity_detected + r.ambiguity_answered_wrongly;
    r.ambiguity_detection_rate = answered > 0 ? static_cast<double>(r.ambiguity_detected) / answered
                                              : std::numeric_limits<double>::quiet_NaN();
    report.results.push_back(r);
  }
  return report;
}

}  // namespace gridloc
