// Seed 002 with the engine in the loop (see engine_disambiguation.hpp).
#include "gridloc/engine/evaluation/engine_disambiguation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "gridloc/engine/disambiguation/grid_space.hpp"
#include "gridloc/engine/evaluation/trials.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {
namespace {

/// What every trial on one map shares.
struct Setting {
  const OccupancyMap& map;
  const SonarRing& ring;
  const CorrelationEstimator& estimator;
  const GridPlanningSpace& space;
  const EngineDisambiguationOptions& options;
};

Observation observe(const Setting& setting, const Pose2& truth, std::uint64_t seed) {
  Observation observation;
  const LaserProtocol& laser = setting.options.laser;
  if (laser.enabled) {
    observation.scan =
        simulate_scan(setting.map, truth, laser.beams, laser.max_range, laser.sigma_m, seed);
  } else {
    observation.ranges =
        simulate_sonar(setting.map, setting.ring, truth, SonarSimOptions::realistic(seed));
  }
  return observation;
}

bool on_free_cell(const OccupancyMap& map, const Pose2& pose) {
  const Pose2 local = map.geometry.to_grid_frame(pose);
  const Cell cell = map.geometry.cell_of(local.x, local.y);
  return map.geometry.contains(cell.ix, cell.iy) && map.at(cell.ix, cell.iy) == CellState::Free;
}

/// The look-alikes the engine's global search leaves (a HypothesisSet's seeds), those on
/// free cells.
std::vector<Pose2> global_hypotheses(const Setting& setting, const Observation& observation) {
  const HypothesisSetOptions& seeding = setting.options.seeding;
  const Estimate global = setting.estimator.estimate(
      observation, setting.estimator.global_window(observation), seeding.max_hypotheses + 1);
  std::vector<Pose2> poses;
  for (const TrackedHypothesis& seed : seed_hypotheses(global, seeding).hypotheses) {
    if (on_free_cell(setting.map, seed.pose)) poses.push_back(seed.pose);
  }
  return poses;
}

int true_hypothesis(const std::vector<Pose2>& hypotheses, const Pose2& truth,
                    const EngineDisambiguationOptions& options) {
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const Pose2& h = hypotheses[i];
    if (std::hypot(h.x - truth.x, h.y - truth.y) <= options.truth_xy &&
        std::abs(normalize_angle(h.theta - truth.theta)) <= options.truth_theta) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

/// Where the robot truly was and where its odometry put it (start frame, heading 0: the
/// robot keeps the start's heading).
struct DriveSample {
  Pose2 truth;
  Pose2 odometry;
};

/// The robot driving the planner's routes: one length scale and one heading drift per metre
/// for the whole run (as drifting_odometry draws them), applied to every route segment. A
/// point robot: it stops where its drift would take it off the free cells (a bump).
class DriftingRobot {
 public:
  DriftingRobot(const OccupancyMap& map, const Pose2& true_start, const OdometryNoise& noise,
                Rng& rng)
      : map_(map),
        truth_(true_start),
        scale_(1.0 + noise.frac * rng.gaussian()),
        drift_per_m_(noise.rad_per_m * rng.gaussian()) {}

  /// Drives `route` (start-frame points, from where the robot believes it is), sampling its
  /// true and odometry poses every `every_m` along the way and at the end.
  std::vector<DriveSample> drive(const std::vector<Eigen::Vector2d>& route, double every_m) {
    bumped_ = false;
    std::vector<DriveSample> samples;
    double since_sample = every_m;  // the route's first point is sampled
    for (std::size_t k = 0; k + 1 < route.size(); ++k) {
      const Eigen::Vector2d segment = route[k + 1] - route[k];
      const int steps = std::max(1, static_cast<int>(std::ceil(segment.norm() / kStepM)));
      for (int i = 0; i < steps; ++i) {
        if (since_sample >= every_m) {
          samples.push_back(sample(route[k] + segment * (static_cast<double>(i) / steps)));
          since_sample = 0.0;
        }
        step(segment / steps);
        since_sample += segment.norm() / steps;
      }
    }
    samples.push_back(sample(route.empty() ? Eigen::Vector2d::Zero() : route.back()));
    return samples;
  }

 private:
  static constexpr double kStepM = 0.05;

  DriveSample sample(const Eigen::Vector2d& believed) const {
    return {truth_, Pose2{believed.x(), believed.y(), 0.0}};
  }

  void step(const Eigen::Vector2d& commanded) {
    if (bumped_) return;
    const double turn = drift_per_m_ * commanded.norm();
    const double heading = normalize_angle(truth_.theta + 0.5 * turn);
    const double c = std::cos(heading), s = std::sin(heading);
    const Pose2 next{truth_.x + scale_ * (c * commanded.x() - s * commanded.y()),
                     truth_.y + scale_ * (s * commanded.x() + c * commanded.y()),
                     normalize_angle(truth_.theta + turn)};
    if (!on_free_cell(map_, next)) {
      bumped_ = true;  // stays for the rest of the route: a wall is in the way
      return;
    }
    truth_ = next;
  }

  const OccupancyMap& map_;
  Pose2 truth_;
  double scale_ = 1.0;
  double drift_per_m_ = 0.0;
  bool bumped_ = false;
};

/// The observation at the end of a leg: every sample's firing (or scan) fused in the frame
/// of the last (drive fusion, as the Localizer does), so that the whole leg's evidence counts.
Observation observe_leg(const Setting& setting, const std::vector<DriveSample>& samples,
                        std::uint64_t seed) {
  const LaserProtocol& laser = setting.options.laser;
  const DriveWindowOptions window = setting.options.drive;
  Observation observation;
  if (laser.enabled) {
    std::vector<OdometryScan> scans;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      scans.push_back(
          {samples[k].odometry, simulate_scan(setting.map, samples[k].truth, laser.beams,
                                              laser.max_range, laser.sigma_m, seed + k)});
    }
    observation.points =
        fuse_scans(scans, Pose2{}, setting.estimator.options().scan, window).points;
    return observation;
  }
  std::vector<OdometryFiring> firings;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    firings.push_back(
        {samples[k].odometry, simulate_sonar(setting.map, setting.ring, samples[k].truth,
                                             SonarSimOptions::realistic(seed + k))});
  }
  FusedFirings fused = fuse_firings(setting.ring, firings, window);
  observation.ranges = std::move(fused.ranges);
  observation.ring = std::move(fused.ring);
  return observation;
}

/// The engine in the loop: drive, observe with noise, score around each prediction, refit
/// the hypotheses that stand to where the engine found the robot.
class EngineSensing {
 public:
  EngineSensing(const Setting& setting, std::vector<Pose2> hypotheses, DriftingRobot& robot,
                std::uint64_t seed)
      : setting_(&setting),
        hypotheses_(std::move(hypotheses)),
        evidence_(hypotheses_.size(), 0.0),
        robot_(&robot),
        seed_(seed) {}

  StopReading operator()(const Eigen::Vector2d& stop, const std::vector<Eigen::Vector2d>& route,
                         const std::vector<int>& active) {
    const std::vector<DriveSample> samples = robot_->drive(route, setting_->options.firing_every_m);
    const Observation observation = observe_leg(*setting_, samples, seed_ + 7919u * ++stops_);
    // The hypotheses were refit at the previous stop: odometry error grows from there.
    const std::vector<Estimate> estimates =
        score_predictions(setting_->estimator, observation, predictions(stop, active),
                          path_length(route), setting_->options.elimination);
    std::vector<double> totals;
    for (std::size_t k = 0; k < active.size(); ++k) {
      totals.push_back(evidence_[static_cast<std::size_t>(active[k])] += estimates[k].score);
    }
    return refit_kept(within_drop_ratio(totals, setting_->options.elimination.drop_ratio),
                      estimates, stop, active);
  }

 private:
  static double path_length(const std::vector<Eigen::Vector2d>& route) {
    double length = 0.0;
    for (std::size_t k = 1; k < route.size(); ++k) length += (route[k] - route[k - 1]).norm();
    return length;
  }

  /// Where each active hypothesis puts the robot, heading the start's (it keeps its heading).
  std::vector<Pose2> predictions(const Eigen::Vector2d& stop,
                                 const std::vector<int>& active) const {
    std::vector<Pose2> predicted;
    for (const int index : active) {
      const Pose2& start = hypotheses_[static_cast<std::size_t>(index)];
      const Eigen::Vector2d at = to_world(start, stop);
      predicted.push_back({at.x(), at.y(), start.theta});
    }
    return predicted;
  }

  /// The kept hypotheses (positions `kept` in `active`, ascending), each refit: the start pose
  /// that puts the robot, believed at `stop` with the start's heading, where the engine found it.
  StopReading refit_kept(const std::vector<int>& kept, const std::vector<Estimate>& estimates,
                         const Eigen::Vector2d& stop, const std::vector<int>& active) {
    const Pose2 to_start = relative_pose(Pose2{stop.x(), stop.y(), 0.0}, Pose2{});
    StopReading reading;
    for (const int k : kept) {
      const int index = active[static_cast<std::size_t>(k)];
      const Pose2 refit = compose(estimates[static_cast<std::size_t>(k)].pose, to_start);
      reading.consistent.push_back(index);
      reading.refit.push_back(refit);
      hypotheses_[static_cast<std::size_t>(index)] = refit;
    }
    return reading;
  }

  const Setting* setting_;
  std::vector<Pose2> hypotheses_;
  std::vector<double> evidence_;  ///< per hypothesis, its scores summed over the stops
  DriftingRobot* robot_;
  std::uint64_t seed_;
  int stops_ = 0;
};

/// Noise-free sensing and motion on the grid twin: a hypothesis stands while its predicted
/// scan at the stop is the same view as the one from the true start's.
StopSensing perfect_grid_sensing(const GridPlanningSpace& space, const Pose2& truth,
                                 const std::vector<Pose2>& hypotheses) {
  return
      [&space, truth, &hypotheses](const Eigen::Vector2d& stop, const std::vector<Eigen::Vector2d>&,
                                   const std::vector<int>& active) {
        std::vector<Pose2> poses{truth};
        for (const int index : active) poses.push_back(hypotheses[static_cast<std::size_t>(index)]);
        const std::vector<int> classes = space.classes(poses, stop);
        StopReading reading;
        for (std::size_t k = 0; k < active.size(); ++k) {
          if (classes[k + 1] == classes[0]) reading.consistent.push_back(active[k]);
        }
        return reading;
      };
}

struct TrialOutcome {
  int hypotheses = 0;
  bool truth_seeded = false, true_survived = false, wrong_answer = false, resolved = false;
  bool noise_free_resolved = false;
  double path_length = 0.0, noise_free_path_length = 0.0, ms = 0.0;
  int stops = 0;
};

TrialOutcome run_trial(const Setting& setting, const Pose2& truth,
                       const std::vector<Pose2>& hypotheses, std::uint64_t seed) {
  TrialOutcome outcome;
  outcome.hypotheses = static_cast<int>(hypotheses.size());
  const int truth_index = true_hypothesis(hypotheses, truth, setting.options);
  outcome.truth_seeded = truth_index >= 0;
  MinimumDistanceOptions planner = setting.options.planner;
  planner.seed = seed;
  const MinimumDistancePlan noise_free = localize_with_minimum_travel(
      setting.space, hypotheses, perfect_grid_sensing(setting.space, truth, hypotheses), planner);
  Rng rng(seed);
  DriftingRobot robot(setting.space.passable(), truth, setting.options.odometry, rng);
  const auto begin = std::chrono::steady_clock::now();
  const MinimumDistancePlan plan = localize_with_minimum_travel(
      setting.space, hypotheses, EngineSensing(setting, hypotheses, robot, seed), planner);
  outcome.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  const auto& left = plan.remaining;
  outcome.true_survived = std::find(left.begin(), left.end(), truth_index) != left.end();
  outcome.resolved = plan.resolved;
  outcome.wrong_answer = plan.resolved && left.front() != truth_index;
  outcome.path_length = plan.path_length;
  outcome.stops = static_cast<int>(plan.stops.size());
  outcome.noise_free_resolved = noise_free.resolved;
  outcome.noise_free_path_length = noise_free.path_length;
  return outcome;
}

double mean_of(const std::vector<TrialOutcome>& outcomes,
               const std::function<double(const TrialOutcome&)>& value) {
  if (outcomes.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const TrialOutcome& outcome : outcomes) sum += value(outcome);
  return sum / static_cast<double>(outcomes.size());
}

double median_ms(const std::vector<TrialOutcome>& outcomes) {
  std::vector<double> ms;
  for (const TrialOutcome& outcome : outcomes) ms.push_back(outcome.ms);
  if (ms.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(ms.begin(), ms.end());
  return ms.size() % 2 == 1 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
}

EngineDisambiguationResult summarize(const std::string& name, int drawn,
                                     const std::vector<TrialOutcome>& outcomes) {
  EngineDisambiguationResult row;
  row.map = name;
  row.trials = static_cast<int>(outcomes.size());
  row.drawn = drawn;
  for (const TrialOutcome& outcome : outcomes) {
    row.truth_seeded += outcome.truth_seeded ? 1 : 0;
    row.wrong_answers += outcome.wrong_answer ? 1 : 0;
  }
  row.true_survived_rate = mean_of(outcomes, [](const TrialOutcome& o) { return o.true_survived; });
  row.resolved_rate = mean_of(outcomes, [](const TrialOutcome& o) { return o.resolved; });
  row.mean_hypotheses = mean_of(outcomes, [](const TrialOutcome& o) { return o.hypotheses; });
  row.mean_path_length = mean_of(outcomes, [](const TrialOutcome& o) { return o.path_length; });
  row.mean_noise_free_path_length =
      mean_of(outcomes, [](const TrialOutcome& o) { return o.noise_free_path_length; });
  row.noise_free_resolved_rate =
      mean_of(outcomes, [](const TrialOutcome& o) { return o.noise_free_resolved; });
  row.mean_stops = mean_of(outcomes, [](const TrialOutcome& o) { return o.stops; });
  row.median_ms = median_ms(outcomes);
  return row;
}

/// The farthest a sonar of the ring hears (m): the planner's sensor range.
double sonar_range(const SonarRing& ring) {
  double range = 0.0;
  for (const SonarSpec& sonar : ring.sonars) range = std::max(range, sonar.max_range);
  return range;
}

CorrelationOptions engine_options(const EngineDisambiguationOptions& options, double ring_reach) {
  CorrelationOptions correlation = options.correlation;
  // The fused drive reaches as far as its oldest firing's sensors (the Localizer's rule).
  correlation.reach_m =
      (options.laser.enabled ? options.laser.max_range : ring_reach) + options.drive.max_distance_m;
  return correlation;
}

/// Every trial on one map: poses drawn until `trials` of them are ambiguous.
EngineDisambiguationResult run_map(const EvalMap& map, const SonarRing& ring,
                                   const EngineDisambiguationOptions& options,
                                   const std::function<void(int)>& trial_done) {
  const CorrelationOptions correlation = engine_options(options, ring.reach());
  const CorrelationEstimator estimator = options.laser.enabled
                                             ? CorrelationEstimator(map.map, correlation)
                                             : CorrelationEstimator(map.map, ring, correlation);
  const double range = options.laser.enabled ? options.laser.max_range : sonar_range(ring);
  const GridPlanningSpace space(map.map, {range, options.equivalence, options.route_clearance_m});
  const Setting setting{map.map, ring, estimator, space, options};
  Rng rng(options.seed);
  std::vector<TrialOutcome> outcomes;
  int drawn = 0;
  const int attempts = options.trials * options.attempts_per_trial;
  while (static_cast<int>(outcomes.size()) < options.trials && drawn < attempts) {
    ++drawn;
    const Pose2 truth = sample_free_pose(map.map, ring, options.clearance_m, rng);
    const std::uint64_t seed = options.seed * 1000003u + static_cast<std::uint64_t>(drawn);
    const std::vector<Pose2> hypotheses = global_hypotheses(setting, observe(setting, truth, seed));
    if (hypotheses.size() < 2) continue;
    outcomes.push_back(run_trial(setting, truth, hypotheses, seed));
    trial_done(static_cast<int>(outcomes.size()));
  }
  return summarize(map.name, drawn, outcomes);
}

}  // namespace

void validate(const EngineDisambiguationOptions& options) {
  if (options.trials < 1) throw Error("engine disambiguation: trials must be >= 1");
  if (options.attempts_per_trial < 1) {
    throw Error("engine disambiguation: attempts_per_trial must be >= 1");
  }
  validate(options.elimination);
  validate(options.odometry);
  validate(options.planner);
  validate(options.seeding);
}

std::vector<EngineDisambiguationResult> run_engine_disambiguation(
    const std::vector<EvalMap>& maps, const SonarRing& ring,
    const EngineDisambiguationOptions& options, const std::function<void(int, int)>& progress) {
  validate(options);
  std::vector<EngineDisambiguationResult> results;
  const int total = options.trials * static_cast<int>(maps.size());
  for (std::size_t m = 0; m < maps.size(); ++m) {
    const int before = options.trials * static_cast<int>(m);
    results.push_back(run_map(maps[m], ring, options, [&](int done) {
      if (progress) progress(before + done, total);
    }));
  }
  return results;
}

}  // namespace gridloc
