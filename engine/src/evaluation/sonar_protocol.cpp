#include "gridloc/engine/evaluation/sonar_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "gridloc/engine/icp/estimator.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "gridloc/sensors/scan_sim.hpp"

namespace gridloc {
namespace {

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

/// True when robot-frame point p is inside the footprint or within `clearance` of it.
bool near_footprint(const Footprint& fp, const Eigen::Vector2d& p, double clearance) {
  if (fp.polygon.size() < 3) return p.norm() <= clearance;
  if (footprint_contains(fp, p)) return true;
  for (std::size_t i = 0, j = fp.polygon.size() - 1; i < fp.polygon.size(); j = i++) {
    if (segment_distance(p, fp.polygon[j], fp.polygon[i]) <= clearance) return true;
  }
  return false;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  return Rng(a * 0x100000001B3ull ^ b).next();
}

}  // namespace

std::string to_string(LocalModel m) {
  return m == LocalModel::Oriented ? "oriented" : "turned";
}
std::string to_string(GlobalModel m) {
  return m == GlobalModel::Thinned ? "thinned" : "raw";
}

Pose2 sample_free_pose(const OccupancyMap& map, const SonarRing& ring, double clearance, Rng& rng) {
  const GridGeometry& g = map.geometry;
  double radius = clearance;
  for (const auto& p : ring.footprint.polygon) radius = std::max(radius, p.norm() + clearance);
  const int r = static_cast<int>(std::ceil(radius / g.resolution)) + 1;
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Pose2 local{rng.uniform(0.0, g.width * g.resolution),
                      rng.uniform(0.0, g.height * g.resolution),
                      rng.uniform(-std::numbers::pi, std::numbers::pi)};
    const Cell c = g.cell_of(local.x, local.y);
    const double cs = std::cos(local.theta), sn = std::sin(local.theta);
    bool clear = true;
    for (int iy = c.iy - r; iy <= c.iy + r && clear; ++iy) {
      for (int ix = c.ix - r; ix <= c.ix + r; ++ix) {
        if (g.contains(ix, iy) && map.at(ix, iy) == CellState::Free) continue;
        const Eigen::Vector2d w = g.cell_center(ix, iy) - Eigen::Vector2d(local.x, local.y);
        const Eigen::Vector2d p(cs * w.x() + sn * w.y(), -sn * w.x() + cs * w.y());
        if (near_footprint(ring.footprint, p, clearance + 0.5 * g.resolution)) {
          clear = false;
          break;
        }
      }
    }
    if (clear) return g.to_world_frame(local);
  }
  throw Error("evaluation: found no free pose with the requested clearance on this map");
}

double auroc(const std::vector<double>& positives, const std::vector<double>& negatives) {
  if (positives.empty() || negatives.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> neg = negatives;
  std::sort(neg.begin(), neg.end());
  double wins = 0.0;  // pairs where the positive scores higher, ties counting half
  for (double p : positives) {
    const auto below = std::lower_bound(neg.begin(), neg.end(), p) - neg.begin();
    const auto not_above = std::upper_bound(neg.begin(), neg.end(), p) - neg.begin();
    wins += static_cast<double>(below) + 0.5 * static_cast<double>(not_above - below);
  }
  return wins / (static_cast<double>(positives.size()) * static_cast<double>(neg.size()));
}

double flagged_at_recall(const std::vector<double>& positives, const std::vector<double>& negatives,
                         double recall) {
  if (positives.empty() || negatives.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> pos = positives;
  std::sort(pos.begin(), pos.end(), std::greater<>());
  // The highest threshold with at least `recall` of the positives at or above it.
  const auto keep = static_cast<std::size_t>(std::ceil(recall * static_cast<double>(pos.size())));
  const double threshold = pos[std::clamp<std::size_t>(keep, 1, pos.size()) - 1];
  const auto flagged =
      std::count_if(negatives.begin(), negatives.end(), [&](double v) { return v < threshold; });
  return static_cast<double>(flagged) / static_cast<double>(negatives.size());
}

OccupancyMap add_furniture(const OccupancyMap& map, const Pose2& keep, double keep_clear,
                           Rng& rng) {
  OccupancyMap world = map;
  const GridGeometry& g = map.geometry;
  const Pose2 k = g.to_grid_frame(keep);
  const int boxes = 2 + static_cast<int>(rng.next() % 3);
  for (int b = 0, attempts = 0; b < boxes && attempts < 200; ++attempts) {
    const double w = rng.uniform(0.3, 0.8), h = rng.uniform(0.3, 0.8);
    const double x0 = rng.uniform(0.0, g.width * g.resolution - w);
    const double y0 = rng.uniform(0.0, g.height * g.resolution - h);
    // The box's nearest point to the kept pose must be keep_clear away.
    const double nx = std::clamp(k.x, x0, x0 + w) - k.x, ny = std::clamp(k.y, y0, y0 + h) - k.y;
    if (std::hypot(nx, ny) < keep_clear) continue;
    const Cell a = g.cell_of(x0, y0), z = g.cell_of(x0 + w, y0 + h);
    bool free = true;
    for (int iy = a.iy; iy <= z.iy && free; ++iy) {
      for (int ix = a.ix; ix <= z.ix && free; ++ix) {
        free = g.contains(ix, iy) && map.at(ix, iy) == CellState::Free;
      }
    }
    if (!free) continue;
    for (int iy = a.iy; iy <= z.iy; ++iy) {
      for (int ix = a.ix; ix <= z.ix; ++ix) world.at(ix, iy) = CellState::Occupied;
    }
    ++b;
  }
  return world;
}

namespace {

/// An estimator shared with another owner (the correlation search of CorrelationIcp).
class SharedEstimator final : public Estimator {
 public:
  explicit SharedEstimator(std::shared_ptr<const Estimator> e) : e_(std::move(e)) {}
  Estimate estimate(const Observation& o, const SearchWindow& w) const override {
    return e_->estimate(o, w);
  }
  std::string name() const override { return e_->name(); }

 private:
  std::shared_ptr<const Estimator> e_;
};

}  // namespace

EvalReport run_evaluation(const std::vector<EvalMap>& maps, const SonarRing& ring,
                          const EvalOptions& options,
                          const std::function<void(int, int)>& progress) {
  if (options.trials < 1) throw Error("evaluation: trials must be >= 1");
  if (maps.empty()) throw Error("evaluation: no maps");
  if (options.echo_filter) {
    validate(*options.echo_filter);
    if (options.echo_firings < 2) {
      throw Error("evaluation: echo_firings must be >= 2, got " +
                  std::to_string(options.echo_firings));
    }
  }
  const LaserProtocol& laser = options.laser;
  if (laser.enabled && options.echo_filter) {
    throw Error("evaluation: the echo filter is for sonar readings, not the laser protocol");
  }
  for (const auto& c : options.configurations) {
    if (is_sector_estimator(c.estimator)) {
      throw Error("evaluation: the " + to_string(c.estimator) +
                  " estimator needs polygon maps and global 360 degree scans: the sector "
                  "protocol (run_sector_evaluation; gridloc eval with polygon --maps)");
    }
    if (c.estimator != EstimatorKind::Correlation && !laser.enabled) {
      throw Error("evaluation: the " + to_string(c.estimator) +
                  " estimator needs laser scans (the laser protocol, gridloc eval --laser): "
                  "ICP finds no tangents in a sonar ring's echoes");
    }
  }
  const std::size_t nc = options.configurations.size();
  std::vector<std::vector<double>> pos_err(nc), head_err(nc), ms(nc);
  std::vector<int> successes(nc, 0);
  const int total = options.trials * static_cast<int>(maps.size());
  int done = 0;
  EvalReport report;

  for (std::size_t m = 0; m < maps.size(); ++m) {
    std::vector<std::unique_ptr<Estimator>> estimators;
    std::shared_ptr<const IcpEstimator> icp;  // one per map, shared by the ICP configurations
    for (const auto& config : options.configurations) {
      CorrelationOptions o = options.search;
      o.local = config.local;
      o.global = config.global;
      o.reach_m = laser.enabled ? laser.max_range : 0.0;
      if (config.estimator != EstimatorKind::Correlation && !icp) {
        icp = std::make_shared<const IcpEstimator>(maps[m].map);
      }
      if (config.estimator == EstimatorKind::Icp) {
        estimators.push_back(std::make_unique<IcpEstimator>(*icp));
        continue;
      }
      auto correlation = laser.enabled
                             ? std::make_shared<CorrelationEstimator>(maps[m].map, o)
                             : std::make_shared<CorrelationEstimator>(maps[m].map, ring, o);
      if (config.estimator == EstimatorKind::CorrelationIcp) {
        estimators.push_back(std::make_unique<CorrelationIcpEstimator>(correlation, icp));
      } else {
        estimators.push_back(std::make_unique<SharedEstimator>(correlation));
      }
    }
    for (int t = 0; t < options.trials; ++t) {
      Rng rng(mix(mix(options.seed, m), static_cast<std::uint64_t>(t)));
      const Pose2 truth = sample_free_pose(maps[m].map, ring, options.clearance_m, rng);
      const NoisyProtocol& noisy = options.noisy;
      SonarSimOptions noise = noisy.enabled ? noisy.noise : options.noise;
      noise.seed = rng.next();
      // Only the noisy protocol draws these, so the plain protocol's draws stay as they were
      // (a noisy run's priors differ from a plain run's).
      const bool furniture = noisy.enabled && rng.uniform(0.0, 1.0) < noisy.furniture_prob;
      bool wrong_prior = noisy.enabled && rng.uniform(0.0, 1.0) < noisy.wrong_prior_prob;
      double footprint_radius = 0.0;
      for (const auto& p : ring.footprint.polygon) {
        footprint_radius = std::max(footprint_radius, p.norm());
      }
      const OccupancyMap* world = &maps[m].map;
      OccupancyMap changed;
      if (furniture) {
        changed = add_furniture(maps[m].map, truth, footprint_radius + 0.3, rng);
        world = &changed;
      }
      Observation obs;
      if (laser.enabled) {
        obs.scan =
            simulate_scan(*world, truth, laser.beams, laser.max_range, laser.sigma_m, noise.seed);
      } else {
        obs.ranges = simulate_sonar(*world, ring, truth, noise);
      }
      int rejected_sonars = 0;
      if (options.echo_filter) {
        // Consecutive firings from the same pose: the first is the unfiltered protocol's
        // reading, the others draw from seeds derived from it (not from `rng`, so that poses
        // and priors stay those of the unfiltered protocol).
        std::vector<std::vector<double>> firings{obs.ranges};
        for (int k = 1; k < options.echo_firings; ++k) {
          SonarSimOptions again = noise;
          again.seed = mix(noise.seed, static_cast<std::uint64_t>(k));
          firings.push_back(simulate_sonar(*world, ring, truth, again));
        }
        FilteredReadings filtered = filter_echoes(ring, firings, *options.echo_filter);
        obs.ranges = std::move(filtered.ranges);
        obs.rejected = std::move(filtered.rejected);
        rejected_sonars = filtered.rejected_count;
      }
      const bool all_rejected = rejected_sonars == static_cast<int>(ring.sonars.size());
      SearchWindow window = options.window;
      window.center = {
          truth.x + rng.uniform(-window.half_xy, window.half_xy),
          truth.y + rng.uniform(-window.half_xy, window.half_xy),
          normalize_angle(truth.theta + rng.uniform(-window.half_theta, window.half_theta))};
      if (wrong_prior) {  // one axis 1.5-3 half sizes off: the truth is outside the window
        const double off = window.half_xy * rng.uniform(1.5, 3.0) * (rng.next() % 2 ? 1 : -1);
        if (rng.next() % 2) {
          window.center.x = truth.x + off;
        } else {
          window.center.y = truth.y + off;
        }
      }
      // A perturbed prior can leave a map whose edge is close; pull it back onto the map.
      const Pose2 g = maps[m].map.geometry.to_grid_frame(window.center);
      const GridGeometry& geo = maps[m].map.geometry;
      const double eps = 1e-6;
      const Pose2 clamped{std::clamp(g.x, eps, geo.width * geo.resolution - eps),
                          std::clamp(g.y, eps, geo.height * geo.resolution - eps), g.theta};
      window.center = geo.to_world_frame(clamped);
      // Pulled back onto the map, a wrong prior may hold the truth again: then it is not one.
      const Pose2 truth_g = geo.to_grid_frame(truth);
      wrong_prior = wrong_prior && std::max(std::abs(truth_g.x - clamped.x),
                                            std::abs(truth_g.y - clamped.y)) > window.half_xy;

      for (std::size_t c = 0; c < nc; ++c) {
        Estimate e;
        if (all_rejected) {  // nothing to localize with: a failure at the prior, no confidence
          e.pose = e.lattice_pose = window.center;
        } else {
          e = estimators[c]->estimate(obs, window);
        }
        const double dp = std::hypot(e.pose.x - truth.x, e.pose.y - truth.y);
        const double dt = std::abs(normalize_angle(e.pose.theta - truth.theta));
        pos_err[c].push_back(dp);
        head_err[c].push_back(rad2deg(dt));
        ms[c].push_back(e.stats.elapsed_ms);
        const bool success = dp <= options.success_xy && dt <= options.success_theta;
        if (success) ++successes[c];
        report.records.push_back({maps[m].name, t, c, success, wrong_prior, furniture, dp,
                                  rad2deg(dt), e, rejected_sonars});
      }
      if (progress) progress(++done, total);
    }
  }

  report.trials = total;
  for (std::size_t c = 0; c < nc; ++c) {
    std::vector<double> good, bad;  // confidences of successes and failures
    for (const TrialRecord& r : report.records) {
      if (r.configuration == c) (r.success ? good : bad).push_back(r.estimate.confidence);
    }
    ConfigurationResult r;
    r.configuration = options.configurations[c];
    r.trials = total;
    r.successes = successes[c];
    r.success_rate = static_cast<double>(successes[c]) / total;
    for (double v : pos_err[c]) r.mean_position_error_m += v / total;
    for (double v : head_err[c]) r.mean_heading_error_deg += v / total;
    r.median_ms = median(ms[c]);
    r.auroc = auroc(good, bad);
    r.failures_flagged_at_95_recall = flagged_at_recall(good, bad, 0.95);
    report.configurations.push_back(r);
  }
  return report;
}

}  // namespace gridloc
