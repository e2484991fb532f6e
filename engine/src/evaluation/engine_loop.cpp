// The simulated wheelchair with the engine in the loop (see engine_loop.hpp).
#include "gridloc/engine/evaluation/engine_loop.hpp"

#include <algorithm>
#include <cmath>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/drive_fusion.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "gridloc/sensors/sonar_sim.hpp"

namespace gridloc {
namespace {

/// Where the robot truly was and where its odometry put it (start frame, heading 0: the
/// robot keeps the start's heading).
struct DriveSample {
  Pose2 truth;
  Pose2 odometry;
};

/// The robot driving the planner's routes: one length scale and one heading drift per metre
/// for the whole run (as drifting_odometry draws them), applied to every route segment. A
/// point robot: it stops where its drift would take it off the cells the chair can reach
/// (a bump).
class DriftingRobot {
 public:
  DriftingRobot(const DisambiguationPlanner& planner, const Pose2& true_start,
                const OdometryNoise& noise, Rng& rng)
      : planner_(planner),
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
    if (!planner_.passable(next)) {
      bumped_ = true;  // stays for the rest of the route: a wall is in the way
      return;
    }
    truth_ = next;
  }

  const DisambiguationPlanner& planner_;
  Pose2 truth_;
  double scale_ = 1.0;
  double drift_per_m_ = 0.0;
  bool bumped_ = false;
};

/// The observation at the end of a leg: every sample's firing (or scan) fused in the frame
/// of the last (drive fusion, as the Localizer does), so that the whole leg's evidence counts.
Observation observe_leg(const EngineLoop& loop, const std::vector<DriveSample>& samples,
                        std::uint64_t seed) {
  const LaserProtocol& laser = loop.options().laser;
  const DriveWindowOptions window = loop.options().drive;
  Observation observation;
  if (laser.enabled) {
    std::vector<OdometryScan> scans;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      scans.push_back(
          {samples[k].odometry, simulate_scan(loop.map(), samples[k].truth, laser.beams,
                                              laser.max_range, laser.sigma_m, seed + k)});
    }
    observation.points = fuse_scans(scans, Pose2{}, loop.estimator().options().scan, window).points;
    return observation;
  }
  std::vector<OdometryFiring> firings;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    firings.push_back(
        {samples[k].odometry, simulate_sonar(loop.map(), loop.ring(), samples[k].truth,
                                             SonarSimOptions::realistic(seed + k))});
  }
  FusedFirings fused = fuse_firings(loop.ring(), firings, window);
  observation.ranges = std::move(fused.ranges);
  observation.ring = std::move(fused.ring);
  return observation;
}

/// The engine in the loop: drive, observe with noise, score around each prediction, refit
/// the hypotheses that stand to where the engine found the robot.
class EngineSensing {
 public:
  EngineSensing(const EngineLoop& loop, std::vector<Pose2> hypotheses, DriftingRobot& robot,
                std::uint64_t seed)
      : loop_(&loop),
        hypotheses_(std::move(hypotheses)),
        evidence_(hypotheses_.size(), 0.0),
        robot_(&robot),
        seed_(seed) {}

  StopReading operator()(const Eigen::Vector2d& stop, const std::vector<Eigen::Vector2d>& route,
                         const std::vector<int>& active) {
    const std::vector<DriveSample> samples = robot_->drive(route, loop_->options().firing_every_m);
    const unsigned stop_seed = 7919u * static_cast<unsigned>(++stops_);  // as before: 32-bit
    const Observation observation = observe_leg(*loop_, samples, seed_ + stop_seed);
    // The hypotheses were refit at the previous stop: odometry error grows from there.
    const std::vector<Estimate> estimates =
        score_predictions(loop_->estimator(), observation, predictions(stop, active),
                          path_length(route), loop_->options().elimination);
    std::vector<double> totals;
    for (std::size_t k = 0; k < active.size(); ++k) {
      totals.push_back(evidence_[static_cast<std::size_t>(active[k])] += estimates[k].score);
    }
    return refit_kept(within_drop_ratio(totals, loop_->options().elimination.drop_ratio), estimates,
                      stop, active);
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

  const EngineLoop* loop_;
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

/// The options checked first, as a whole (their planner's own check follows).
DisambiguationPlannerOptions checked_planner_options(const EngineLoopOptions& options) {
  validate(options);
  return as_planner_options(options);
}

}  // namespace

void validate(const EngineLoopOptions& options) {
  validate(options.elimination);
  validate(options.odometry);
  validate(options.planner);
  validate(options.seeding);
  validate(options.drive);
  if (!(options.firing_every_m > 0.0) || !std::isfinite(options.firing_every_m)) {
    throw Error("engine loop: firing_every_m must be > 0 m");
  }
}

DisambiguationPlannerOptions as_planner_options(const EngineLoopOptions& options) {
  DisambiguationPlannerOptions planner;
  planner.laser = options.laser.enabled;
  planner.laser_range_m = options.laser.max_range;
  planner.correlation = options.correlation;
  planner.seeding = options.seeding;
  planner.drive = options.drive;
  planner.planner = options.planner;
  planner.equivalence = options.equivalence;
  planner.route_clearance_m = options.route_clearance_m;
  return planner;
}

EngineLoop::EngineLoop(const OccupancyMap& map, const SonarRing& ring,
                       const EngineLoopOptions& options)
    : map_(map),
      ring_(ring),
      options_(options),
      planner_(map, ring, checked_planner_options(options)) {}

Observation EngineLoop::observe(const Pose2& truth, std::uint64_t seed) const {
  Observation observation;
  const LaserProtocol& laser = options_.laser;
  if (laser.enabled) {
    observation.scan =
        simulate_scan(map_, truth, laser.beams, laser.max_range, laser.sigma_m, seed);
  } else {
    observation.ranges = simulate_sonar(map_, ring_, truth, SonarSimOptions::realistic(seed));
  }
  return observation;
}

int EngineLoop::true_hypothesis(const std::vector<Pose2>& hypotheses, const Pose2& truth) const {
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const Pose2& h = hypotheses[i];
    if (std::hypot(h.x - truth.x, h.y - truth.y) <= options_.truth_xy &&
        std::abs(normalize_angle(h.theta - truth.theta)) <= options_.truth_theta) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

EngineLoopRun EngineLoop::run(const Pose2& truth, std::vector<Pose2> hypotheses,
                              std::uint64_t seed) const {
  EngineLoopRun run;
  run.hypotheses = std::move(hypotheses);
  run.true_hypothesis = true_hypothesis(run.hypotheses, truth);
  MinimumDistanceOptions planner = options_.planner;
  planner.seed = seed;
  run.noise_free = localize_with_minimum_travel(
      space(), run.hypotheses, perfect_grid_sensing(space(), truth, run.hypotheses), planner);
  Rng rng(seed);
  DriftingRobot robot(planner_, truth, options_.odometry, rng);
  run.plan = localize_with_minimum_travel(
      space(), run.hypotheses, EngineSensing(*this, run.hypotheses, robot, seed), planner);
  return run;
}

}  // namespace gridloc
