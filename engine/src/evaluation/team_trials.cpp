// The team protocol: random teams, their answers judged against the truth.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "gridloc/engine/evaluation/team_protocol.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/planar.hpp"
#include "gridloc/sensors/rng.hpp"

namespace gridloc {

void validate(const TeamProtocolOptions& options) {
  auto require = [](bool ok, const char* message) {
    if (!ok) throw Error(message);
  };
  require(!options.robots.empty(), "team protocol: give at least one team size");
  for (int size : options.robots) require(size >= 1 && size <= 16, "team sizes must be in [1, 16]");
  require(options.trials >= 1, "team protocol trials must be >= 1");
  require(std::isfinite(options.clearance_m) && options.clearance_m >= 0.0,
          "team protocol clearance_m must be >= 0 and finite");
  require(std::isfinite(options.correct_m) && options.correct_m > 0.0,
          "team protocol correct_m must be positive and finite");
  require(std::isfinite(options.correct_theta) && options.correct_theta > 0.0,
          "team protocol correct_theta must be positive and finite");
  require(options.draw_attempts >= 1, "team protocol draw_attempts must be >= 1");
  validate(options.team);
}

namespace {

Eigen::Vector2d position(const Pose2& pose) {
  return {pose.x, pose.y};
}

bool in_free_cell(const OccupancyMap& grid, const Eigen::Vector2d& p) {
  const Pose2 local = grid.geometry.to_grid_frame({p.x(), p.y(), 0.0});
  const Cell cell = grid.geometry.cell_of(local.x, local.y);
  return grid.geometry.contains(cell.ix, cell.iy) && grid.at(cell.ix, cell.iy) == CellState::Free;
}

double wall_distance(const MapFeatures& map, const Eigen::Vector2d& p) {
  return distance_to_nearest(p, map.walls.size(),
                             [&](std::size_t k) -> const MapWall& { return map.walls[k]; });
}

/// A uniformly drawn free cell's point (the first robot).
Eigen::Vector2d free_point(const OccupancyMap& grid, Rng& rng) {
  const Pose2 local{(grid.width() * rng.uniform()) * grid.geometry.resolution,
                    (grid.height() * rng.uniform()) * grid.geometry.resolution, 0.0};
  const Pose2 world = grid.geometry.to_world_frame(local);
  return {world.x, world.y};
}

/// A point within the camera's range of `anchor`.
Eigen::Vector2d linked_point(const Eigen::Vector2d& anchor, const CameraModel& camera, Rng& rng) {
  const double length = rng.uniform(camera.min_range_m, camera.max_range_m);
  const double angle = rng.uniform(-std::numbers::pi, std::numbers::pi);
  return anchor + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

bool acceptable(const TeamSimulator& simulator, const std::vector<Pose2>& team, const Pose2& pose,
                const TeamProtocolOptions& options) {
  const TeamWorld& world = simulator.world();
  const Eigen::Vector2d p = position(pose);
  if (!in_free_cell(world.grid, p) || wall_distance(world.features, p) < options.clearance_m)
    return false;
  const double spacing =
      std::max(2.0 * options.clearance_m, simulator.sensing().camera.min_range_m);
  for (const Pose2& other : team)
    if ((position(other) - p).norm() < spacing) return false;
  if (simulator.sensing().sensor != TeamSensor::Ir) return true;
  TeamSensing exact = simulator.sensing();
  exact.noise = false;
  const TeamSimulator noise_free(world, exact);
  return !noise_free.simulate({pose}, 1).features.front().empty();
}

}  // namespace

std::vector<Pose2> draw_team(const TeamSimulator& simulator, int count,
                             const TeamProtocolOptions& options, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Pose2> team;
  const CameraModel& camera = simulator.sensing().camera;
  while (static_cast<int>(team.size()) < count) {
    bool placed = false;
    for (int attempt = 0; attempt < options.draw_attempts && !placed; ++attempt) {
      const std::size_t anchor = team.empty() ? 0 : rng.next() % team.size();
      const Eigen::Vector2d p = team.empty() ? free_point(simulator.world().grid, rng)
                                             : linked_point(position(team[anchor]), camera, rng);
      const Pose2 pose{p.x(), p.y(), rng.uniform(-std::numbers::pi, std::numbers::pi)};
      if (!acceptable(simulator, team, pose, options)) continue;
      if (!team.empty() && !line_of_sight(simulator.world().features, position(team[anchor]), p))
        continue;
      team.push_back(pose);
      placed = true;
    }
    if (!placed)
      throw Error("team protocol: no place found for robot " + std::to_string(team.size()) +
                  " in " + std::to_string(options.draw_attempts) + " attempts");
  }
  return team;
}

TeamOutcome judge(const TeamAnswer& answer, const std::vector<Pose2>& truth,
                  const TeamProtocolOptions& options) {
  TeamOutcome outcome;
  outcome.verdict = answer.verdict;
  if (answer.solutions.empty()) return outcome;
  const auto& poses = answer.solutions.front().poses;
  for (std::size_t r = 0; r < truth.size(); ++r) {
    outcome.max_position_error_m =
        std::max(outcome.max_position_error_m, (position(poses[r]) - position(truth[r])).norm());
    outcome.max_heading_error = std::max(
        outcome.max_heading_error, std::abs(normalize_angle(poses[r].theta - truth[r].theta)));
  }
  outcome.correct = outcome.max_position_error_m <= options.correct_m &&
                    outcome.max_heading_error <= options.correct_theta;
  return outcome;
}

namespace {

struct Tally {
  int trials = 0, unique_correct = 0, ambiguous = 0, not_localized = 0, wrong = 0;
  double position_error = 0.0, heading_error = 0.0;
  int robots_measured = 0;
  std::vector<double> ms;
};

void count(Tally& tally, const TeamAnswer& answer, const std::vector<Pose2>& truth,
           const TeamProtocolOptions& options) {
  const TeamOutcome outcome = judge(answer, truth, options);
  ++tally.trials;
  if (outcome.verdict == Verdict::Ambiguous) ++tally.ambiguous;
  if (outcome.verdict == Verdict::NotLocalized) ++tally.not_localized;
  if (outcome.verdict != Verdict::Localized) return;
  if (outcome.correct)
    ++tally.unique_correct;
  else
    ++tally.wrong;
  const auto& poses = answer.solutions.front().poses;
  for (std::size_t r = 0; r < truth.size(); ++r) {
    tally.position_error += (position(poses[r]) - position(truth[r])).norm();
    tally.heading_error += std::abs(normalize_angle(poses[r].theta - truth[r].theta));
    ++tally.robots_measured;
  }
}

TeamConfiguration summarize(int robots, Tally& tally) {
  TeamConfiguration configuration;
  configuration.robots = robots;
  configuration.trials = tally.trials;
  const double trials = std::max(1, tally.trials);
  configuration.unique_correct_rate = tally.unique_correct / trials;
  configuration.ambiguous_rate = tally.ambiguous / trials;
  configuration.not_localized_rate = tally.not_localized / trials;
  configuration.wrong_localized = tally.wrong;
  const double measured = std::max(1, tally.robots_measured);
  configuration.mean_position_error_m = tally.position_error / measured;
  configuration.mean_heading_error_deg = tally.heading_error / measured * 180.0 / std::numbers::pi;
  if (!tally.ms.empty()) {
    std::nth_element(tally.ms.begin(), tally.ms.begin() + tally.ms.size() / 2, tally.ms.end());
    configuration.median_ms = tally.ms[tally.ms.size() / 2];
  }
  return configuration;
}

/// One trial: a team's sensing simulated, then localized (timed: features onwards).
TeamAnswer run_trial(const TeamSimulator& simulator, const TeamCase& team,
                     const TeamProtocolOptions& options) {
  try {
    return localize_team(team.robots, team.links, simulator.world().features, options.team);
  } catch (const Error&) {  // no robot saw a feature: nothing to place the team by
    TeamAnswer none;
    none.robots.resize(team.truth.size());
    return none;
  }
}

void merge(Tally& into, const Tally& from) {
  into.trials += from.trials;
  into.unique_correct += from.unique_correct;
  into.ambiguous += from.ambiguous;
  into.not_localized += from.not_localized;
  into.wrong += from.wrong;
  into.position_error += from.position_error;
  into.heading_error += from.heading_error;
  into.robots_measured += from.robots_measured;
  into.ms.insert(into.ms.end(), from.ms.begin(), from.ms.end());
}

Tally run_size(const TeamSimulator& simulator, int size, const TeamProtocolOptions& options,
               const std::function<void()>& step) {
  Tally tally;
  for (int trial = 0; trial < options.trials; ++trial) {
    const std::uint64_t seed = options.seed * 1000003ull + size * 10007ull + trial;
    const std::vector<Pose2> truth = draw_team(simulator, size, options, seed);
    const auto start = std::chrono::steady_clock::now();
    const TeamCase team = simulator.simulate(truth, seed);
    const TeamAnswer answer = run_trial(simulator, team, options);
    tally.ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    count(tally, answer, truth, options);
    step();
  }
  return tally;
}

}  // namespace

TeamProtocolReport run_team_protocol(const std::vector<const TeamSimulator*>& worlds,
                                     const TeamProtocolOptions& options,
                                     const std::function<void(int, int)>& progress) {
  validate(options);
  const int total = static_cast<int>(worlds.size() * options.robots.size()) * options.trials;
  int done = 0;
  const auto step = [&] {
    ++done;
    if (progress) progress(done, total);
  };
  TeamProtocolReport report;
  std::vector<Tally> overall(options.robots.size());
  for (const TeamSimulator* world : worlds) {
    report.per_world.emplace_back();
    for (std::size_t k = 0; k < options.robots.size(); ++k) {
      Tally tally = run_size(*world, options.robots[k], options, step);
      merge(overall[k], tally);
      report.per_world.back().push_back(summarize(options.robots[k], tally));
    }
  }
  for (std::size_t k = 0; k < options.robots.size(); ++k)
    report.overall.push_back(summarize(options.robots[k], overall[k]));
  return report;
}

}  // namespace gridloc
