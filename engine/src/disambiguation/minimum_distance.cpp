// Seed 002 §IV-C (COL) and §IV-D (UAL): the hypothesis elimination loop.
#include "gridloc/engine/disambiguation/minimum_distance.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>

#include "gridloc/engine/disambiguation/polygon_space.hpp"
#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

/// The most random points one stop draws over all its rounds (seed 002 step 8 doubles them).
constexpr long long kMaxPointsPerStop = 1 << 22;

struct ScoredPoint {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  double info = 0.0;
  double value = 0.0;
};

/// The best point of one stop's sampling rounds, and how many were drawn.
struct StopChoice {
  std::optional<ScoredPoint> best;
  int sampled = 0;
  int useful = 0;
  bool sampled_useful = false;
};

/// Everything one stop's choice reads.
struct StopContext {
  const PlanningSpace& space;
  const std::vector<Pose2>& active;  ///< the poses of the hypotheses still standing
  const MinimumDistanceOptions& options;
};

std::vector<Pose2> poses_of(const std::vector<Pose2>& hypotheses, const std::vector<int>& active) {
  std::vector<Pose2> poses;
  poses.reserve(active.size());
  for (const int index : active) poses.push_back(hypotheses[static_cast<std::size_t>(index)]);
  return poses;
}

struct PointScore {
  double info = 0.0;
  double distance = std::numeric_limits<double>::infinity();
};

/// Every point's info and distance, on `threads` threads (each point on its own: the same
/// numbers whatever the threads).
std::vector<PointScore> point_scores(const StopContext& context,
                                     const std::vector<Eigen::Vector2d>& points,
                                     const OverlayPaths& distance_from) {
  std::vector<PointScore> scores(points.size());
  std::exception_ptr failure;
  const int threads = context.options.threads;
  const long count = static_cast<long>(points.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads) if (threads > 1)
  for (long i = 0; i < count; ++i) {
    try {
      PointScore& score = scores[static_cast<std::size_t>(i)];
      score.info = context.space.info(context.active, points[static_cast<std::size_t>(i)]);
      if (score.info > 0.0) {
        score.distance = distance_from.distance_to(points[static_cast<std::size_t>(i)]);
      }
    } catch (...) {  // an exception must not leave the parallel region
#pragma omp critical(gridloc_point_scores)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  return scores;
}

/// Scores one round of points; keeps the first of the highest Value (ties: lowest index).
void score_round(const StopContext& context, const std::vector<Eigen::Vector2d>& points,
                 const OverlayPaths& distance_from, StopChoice& choice) {
  const std::vector<PointScore> scores = point_scores(context, points, distance_from);
  for (std::size_t i = 0; i < points.size(); ++i) {
    ++choice.sampled;
    const PointScore& score = scores[i];
    if (!(score.info > 0.0) || !std::isfinite(score.distance)) continue;
    if (score.distance < context.options.min_travel_m) continue;
    ++choice.useful;
    // seed 002 §IV-A: Value = info / distance_OI
    const double value = score.info / std::max(score.distance, 1e-9);
    if (!choice.best || value > choice.best->value) {
      choice.best = ScoredPoint{points[i], score.info, value};
    }
  }
}

/// Seed 002 steps 6-8: draw points, score them, and while none is useful draw twice as many.
StopChoice choose_stop(const StopContext& context, const StopOverlay& overlay,
                       const OverlayPaths& distance_from, Rng& rng) {
  StopChoice choice;
  long long count = context.options.points;
  for (int round = 0; round < context.options.rounds && !choice.best; ++round) {
    if (choice.sampled + count > kMaxPointsPerStop) break;  // the doubling's budget is spent
    const std::vector<Eigen::Vector2d> points = overlay.sample(
        context.options.algorithm, static_cast<int>(count), rng, choice.sampled_useful);
    score_round(context, points, distance_from, choice);
    count *= 2;
  }
  return choice;
}

std::vector<int> ruled_out(const std::vector<int>& active, const std::vector<int>& remaining) {
  std::vector<int> eliminated;
  for (const int index : active) {
    if (std::find(remaining.begin(), remaining.end(), index) == remaining.end()) {
      eliminated.push_back(index);
    }
  }
  return eliminated;
}

/// The sensing's answer must name standing hypotheses, each once.
void check_reading(const StopReading& reading, const std::vector<int>& active) {
  std::vector<int> seen;
  for (const int index : reading.consistent) {
    if (std::find(active.begin(), active.end(), index) == active.end() ||
        std::find(seen.begin(), seen.end(), index) != seen.end()) {
      throw Error("disambiguation: the sensing kept hypothesis " + std::to_string(index) +
                  ", which is not standing or is named twice");
    }
    seen.push_back(index);
  }
}

/// The sensing's refit start poses, where it gave them.
void take_refits(const StopReading& reading, std::vector<Pose2>& hypotheses) {
  if (reading.refit.empty()) return;
  if (reading.refit.size() != reading.consistent.size()) {
    throw Error("disambiguation: the sensing refit " + std::to_string(reading.refit.size()) +
                " poses for " + std::to_string(reading.consistent.size()) + " hypotheses");
  }
  for (std::size_t k = 0; k < reading.consistent.size(); ++k) {
    hypotheses[static_cast<std::size_t>(reading.consistent[k])] = reading.refit[k];
  }
}

/// One stop: overlay, choice, the route there. Empty when no useful point was found.
std::optional<LocalizationStop> plan_stop(const StopContext& context,
                                          const Eigen::Vector2d& current, Rng& rng) {
  // OI holds the robot (the start's OI grows as hypotheses go; an engine's refits may move the
  // start out of it, and then the standard weighted strategy measures from here too).
  const std::unique_ptr<StopOverlay> overlay = context.space.overlay(context.active, current);
  const std::unique_ptr<OverlayPaths> from_current = overlay->paths_from(current);
  const bool weighted = context.options.strategy == DistanceStrategy::Weighted &&
                        overlay->oi_contains(Eigen::Vector2d::Zero());
  const std::unique_ptr<OverlayPaths> from_start =
      weighted ? overlay->paths_from(Eigen::Vector2d::Zero()) : nullptr;
  const StopChoice choice =
      choose_stop(context, *overlay, weighted ? *from_start : *from_current, rng);
  if (!choice.best) return std::nullopt;
  LocalizationStop stop;
  stop.point = choice.best->point;
  stop.info = choice.best->info;
  stop.value = choice.best->value;
  stop.sampled = choice.sampled;
  stop.useful = choice.useful;
  stop.sampled_useful = choice.sampled_useful;
  stop.route = from_current->path_to(stop.point);
  stop.route_length = from_current->distance_to(stop.point);
  return stop;
}

}  // namespace

void validate(const MinimumDistanceOptions& options) {
  if (options.points < 1 || options.points > 1000000) {
    throw Error("disambiguation: points must be in [1, 1000000]");
  }
  if (!(options.min_travel_m >= 0.0) || !std::isfinite(options.min_travel_m)) {
    throw Error("disambiguation: min_travel_m must be a finite number of metres >= 0");
  }
  if (options.rounds < 1) throw Error("disambiguation: rounds must be >= 1");
  if (options.max_stops < 1) throw Error("disambiguation: max_stops must be >= 1");
  if (options.threads < 1 || options.threads > 64) {
    throw Error("disambiguation: threads must be in [1, 64]");
  }
}

StopSensing perfect_sensing(const Area& free_world, const Pose2& true_start,
                            const std::vector<Pose2>& hypotheses, double range, double tolerance) {
  return [free_world, true_start, hypotheses, range, tolerance](const Eigen::Vector2d& stop,
                                                                const std::vector<Eigen::Vector2d>&,
                                                                const std::vector<int>& active) {
    const RangeView sensed =
        range_view(free_world, to_world(true_start, stop), true_start.theta, range);
    StopReading reading;
    for (const int index : active) {
      const Pose2& start = hypotheses[static_cast<std::size_t>(index)];
      const RangeView predicted = range_view(free_world, to_world(start, stop), start.theta, range);
      if (same_view(predicted, sensed, tolerance)) reading.consistent.push_back(index);
    }
    return reading;
  };
}

std::vector<Eigen::Vector2d> world_path(const MinimumDistancePlan& plan, int hypothesis) {
  const std::size_t h = static_cast<std::size_t>(hypothesis);
  std::vector<Eigen::Vector2d> path{to_world(plan.hypotheses.at(h), Eigen::Vector2d::Zero())};
  for (const LocalizationStop& stop : plan.stops) {
    const Pose2& start = stop.frame.empty() ? plan.hypotheses[h] : stop.frame.at(h);
    for (std::size_t k = 1; k < stop.route.size(); ++k) {
      path.push_back(to_world(start, stop.route[k]));
    }
  }
  return path;
}

std::vector<Eigen::Vector2d> whole_path(const MinimumDistancePlan& plan) {
  std::vector<Eigen::Vector2d> path{Eigen::Vector2d::Zero()};
  for (const LocalizationStop& stop : plan.stops) {
    for (std::size_t k = 1; k < stop.route.size(); ++k) path.push_back(stop.route[k]);
  }
  return path;
}

MinimumDistancePlan localize_with_minimum_travel(const PlanningSpace& space,
                                                 const std::vector<Pose2>& hypotheses,
                                                 const StopSensing& sense,
                                                 const MinimumDistanceOptions& options) {
  validate(options);
  if (hypotheses.empty()) throw Error("disambiguation: no hypothesis to tell apart");
  MinimumDistancePlan plan;
  plan.hypotheses = plan.refit = hypotheses;
  std::vector<int> active(hypotheses.size());
  for (std::size_t i = 0; i < active.size(); ++i) active[i] = static_cast<int>(i);
  Eigen::Vector2d current = Eigen::Vector2d::Zero();
  Rng rng(options.seed);
  while (active.size() > 1 && plan.ended.empty()) {
    if (static_cast<int>(plan.stops.size()) >= options.max_stops) {
      plan.ended = "stop limit";
      break;
    }
    const std::vector<Pose2> standing = poses_of(plan.refit, active);
    std::optional<LocalizationStop> stop =
        plan_stop(StopContext{space, standing, options}, current, rng);
    if (!stop) {
      plan.ended = "no useful point";
      break;
    }
    stop->frame = plan.refit;  // the poses this stop was planned with
    const StopReading reading = sense(stop->point, stop->route, active);  // seed 002 step 10
    check_reading(reading, active);
    const std::vector<int>& remaining = reading.consistent;
    take_refits(reading, plan.refit);
    stop->eliminated = ruled_out(active, remaining);
    plan.path_length += stop->route_length;
    current = stop->point;
    active = remaining;
    plan.stops.push_back(std::move(*stop));
    if (active.empty()) plan.ended = "nothing consistent";
  }
  plan.remaining = active;
  plan.resolved = active.size() == 1;
  if (plan.resolved) plan.ended = "resolved";
  return plan;
}

}  // namespace gridloc
