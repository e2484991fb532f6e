// How sure the correlation estimator is: distinct peaks, the winner's covariance, the sonar
// readings' agreement, the confidence and the verdict (engine/doc/correlation.md, "Knowing when it
// is wrong").
#include "confidence.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "gridloc/engine/correlation/row_scores.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {
namespace correlation_detail {

/// The neighbourhood of `p` whose poses are not distinct from it: within distinct_xy and
/// distinct_theta, in lattice units (one definition for every strategy, so that they agree
/// exactly on the second peak).
double heading_turn(const Lattice& lattice) {
  const double turn = 2.0 * std::numbers::pi;
  const double covered = lattice.step_theta * (lattice.headings - 1);
  return lattice.headings > 1 && covered >= turn - lattice.step_theta - 1e-9
             ? turn / lattice.step_theta
             : 0.0;
}

Exclusion neighbourhood(const LatticePose& p, double res, const Lattice& lattice,
                        const CorrelationOptions& options) {
  return {p, options.distinct_xy / res,
          static_cast<int>(std::floor(options.distinct_theta / lattice.step_theta + 1e-9)),
          heading_turn(lattice)};
}

/// Distinct local maxima of the scored poses: best first (ties to the lowest index), each
/// outside the neighbourhood of every one chosen before.
std::vector<LatticePose> distinct_peaks(std::vector<LatticePose> scored, double res,
                                        const Lattice& lattice, const CorrelationOptions& options,
                                        std::size_t max_count) {
  std::sort(scored.begin(), scored.end(), better);  // a total order: any scoring order
  std::vector<LatticePose> peaks;
  for (const auto& c : scored) {
    const bool distinct = std::none_of(peaks.begin(), peaks.end(), [&](const LatticePose& p) {
      return neighbourhood(p, res, lattice, options).contains(c.ix, c.iy, c.it);
    });
    if (distinct) peaks.push_back(c);
    if (peaks.size() == max_count) break;
  }
  return peaks;
}

/// Covariance of the pose around the lattice winner `best`: every lattice pose within k
/// cells and k heading steps is scored, and read as a likelihood p ∝ exp(S - S_best) (the
/// score as a log-likelihood: one nat per fully matched unit-weight cell, the reading of a
/// correlation score real-time correlative matching uses); the weighted covariance of
/// (x, y, theta) plus the lattice's own quantization variance (step^2 / 12 per axis), rotated
/// into the world frame by the map's yaw.
std::vector<Eigen::Matrix3d> peak_covariances(const LatticePose& best, const Lattice& lattice,
                                              const PaddedGrid& global,
                                              const std::function<PlacedLocalGrid(int)>& placed_at,
                                              int k, double yaw,
                                              const std::vector<double>& temperatures) {
  const double res = global.grid.geometry.resolution;
  const std::size_t n = temperatures.size();
  std::vector<Eigen::Vector3d> mean(n, Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> second(n, Eigen::Matrix3d::Zero());
  std::vector<double> total(n, 0.0);
  // A lattice that goes all the way round wraps: the neighbours of heading 0 include the last.
  const bool round = lattice.headings * std::abs(lattice.step_theta) >= 2.0 * std::numbers::pi;
  const int t0 = round ? best.it - k : std::max(0, best.it - k);
  const int t1 = round ? best.it + k : std::min(lattice.headings - 1, best.it + k);
  std::vector<double> scores;  // one row's
  for (int t = t0; t <= t1; ++t) {
    const int it = (t % lattice.headings + lattice.headings) % lattice.headings;
    const PlacedLocalGrid placed = placed_at(it);
    const int x0 = std::max(lattice.x0, best.ix - k), x1 = std::min(lattice.x1, best.ix + k);
    for (int iy = std::max(lattice.y0, best.iy - k); iy <= std::min(lattice.y1, best.iy + k);
         ++iy) {
      scores.resize(static_cast<std::size_t>(x1 - x0 + 1));
      score_row(global, placed, x0, iy, x1 - x0 + 1, scores.data());
      for (int ix = x0; ix <= x1; ++ix) {
        const double below = std::min(0.0, scores[static_cast<std::size_t>(ix - x0)] - best.score);
        // Offsets from the winner: metres, metres, radians.
        const Eigen::Vector3d d((ix - best.ix) * res, (iy - best.iy) * res,
                                (t - best.it) * lattice.step_theta);
        for (std::size_t m = 0; m < n; ++m) {
          const double w = std::exp(below / temperatures[m]);
          total[m] += w;
          mean[m] += w * d;
          second[m] += w * d * d.transpose();
        }
      }
    }
  }
  Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();  // grid frame -> world frame
  rotate.topLeftCorner<2, 2>() << std::cos(yaw), -std::sin(yaw), std::sin(yaw), std::cos(yaw);
  std::vector<Eigen::Matrix3d> out;
  for (std::size_t m = 0; m < n; ++m) {
    mean[m] /= total[m];
    Eigen::Matrix3d cov = second[m] / total[m] - mean[m] * mean[m].transpose();
    cov(0, 0) += res * res / 12.0;
    cov(1, 1) += res * res / 12.0;
    cov(2, 2) += lattice.step_theta * lattice.step_theta / 12.0;
    out.push_back(rotate * cov * rotate.transpose());
  }
  return out;
}

Eigen::Matrix3d peak_covariance(const LatticePose& best, const Lattice& lattice,
                                const PaddedGrid& global,
                                const std::function<PlacedLocalGrid(int)>& placed_at, int k,
                                double yaw, double temperature) {
  return peak_covariances(best, lattice, global, placed_at, k, yaw, {temperature}).front();
}

Eigen::Matrix3d spanning_peaks(const Eigen::Matrix3d& around_winner,
                               const std::vector<Hypothesis>& peaks, double temperature) {
  if (peaks.size() < 2 || !(temperature > 0.0)) return around_winner;
  const Hypothesis& winner = peaks.front();
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  double total = 1.0;  // the winner's own weight
  for (std::size_t k = 1; k < peaks.size(); ++k) {
    const double weight = std::exp((peaks[k].score - winner.score) / temperature);
    const Eigen::Vector3d offset(peaks[k].pose.x - winner.pose.x, peaks[k].pose.y - winner.pose.y,
                                 normalize_angle(peaks[k].pose.theta - winner.pose.theta));
    spread += weight * offset * offset.transpose();
    total += weight;
  }
  return around_winner + spread / total;
}

double position_spread(const Eigen::Matrix3d& covariance) {
  return std::sqrt(std::max(0.0, covariance(0, 0) + covariance(1, 1)));
}

/// Fills the confidence, its parts, the ambiguity flag and the verdict of `e`
/// (engine/doc/correlation.md, "Knowing when it is wrong"). `searched_second`: a distinct
/// hypothesis was looked for.
void judge(Estimate& e, bool searched_second, const VerdictOptions& v) {
  ConfidenceParts& c = e.confidence_parts;
  c.fit = std::clamp(e.normalized_score, 0.0, 1.0);
  c.agreement = std::isnan(e.agreement) ? 1.0 : e.agreement;
  const double distinct =
      e.score > 0.0 ? std::clamp((e.score - e.second_score) / e.score, 0.0, 1.0) : 0.0;
  c.distinctness = searched_second ? distinct / (distinct + v.distinct_scale) : 1.0;
  c.sharpness = std::exp(-c.spread_m / v.spread_scale_m);
  e.confidence = c.agreement * c.fit * c.distinctness * c.sharpness;
  e.ambiguous = false;
  for (std::size_t k = 1; k < e.alternatives.size(); ++k) {
    const Hypothesis& h = e.alternatives[k];
    const double far = std::hypot(h.pose.x - e.lattice_pose.x, h.pose.y - e.lattice_pose.y);
    const double turn = std::abs(normalize_angle(h.pose.theta - e.lattice_pose.theta));
    if (h.score >= v.ambiguity_ratio * e.score && e.score > 0.0 &&
        (far > v.ambiguity_xy || turn > v.ambiguity_theta)) {
      e.ambiguous = true;
    }
  }
  const bool rising = v.rising_edge_not_localized && e.rises_past_window_edge;
  e.verdict = e.ambiguous                                         ? Verdict::Ambiguous
              : e.confidence >= v.localized_confidence && !rising ? Verdict::Localized
                                                                  : Verdict::NotLocalized;
}

/// Estimate::agreement: the share of `ranges` that a noise-free simulation on `map` at
/// `pose` reproduces within 10 cm + 5 % (or both without echo); sonars flagged in `rejected`
/// are left out.
double reading_agreement(const OccupancyMap& map, const SonarRing& ring,
                         const std::vector<double>& ranges, const std::vector<bool>& rejected,
                         const Pose2& pose) {
  // A winner whose cell centre lies past the map's edge (the last cell of a coarse grid
  // overhangs it) has no map around it to simulate: nothing agrees.
  const Pose2 in_grid = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(in_grid.x, in_grid.y);
  if (!map.geometry.contains(cell.ix, cell.iy)) return 0.0;
  const std::vector<double> expected = simulate_sonar(map, ring, pose);
  int agree = 0, used = 0;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    if (i < rejected.size() && rejected[i]) continue;
    ++used;
    const double limit = ring.sonars[i].max_range;
    const bool none = ranges[i] >= limit, none_expected = expected[i] >= limit;
    const bool both_none = none && none_expected;
    const bool both_near =
        !none && !none_expected && std::abs(ranges[i] - expected[i]) <= 0.10 + 0.05 * expected[i];
    if (both_none || both_near) ++agree;
  }
  return used == 0 ? 0.0 : static_cast<double>(agree) / static_cast<double>(used);
}

}  // namespace correlation_detail

std::string to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Localized:
      return "localized";
    case Verdict::Ambiguous:
      return "ambiguous";
    case Verdict::NotLocalized:
      return "not localized";
  }
  return "unknown";
}

}  // namespace gridloc
