#pragma once
/// Team localization simulated and evaluated (seed 003 ch. V, issue 16): each robot's sensing
/// at its true pose (the rotating IR sensor and its features, or a laser or sonar ring through
/// the correlation engine), the links the team can measure, and the protocol of random teams
/// in free space with lines of sight between linked robots.
/// A robot's sensing turned into candidates (TeamWorld, TeamSensing, TeamCase,
/// TeamCandidates) is engine/team/team_sensing.hpp's: a robot application needs no protocol.
#include <cstdint>
#include <functional>
#include <vector>

#include "gridloc/engine/team/team_sensing.hpp"

namespace gridloc {

/// Simulates teams on one world: each robot's sensing at its true pose, turned into its
/// candidates by the TeamCandidates it holds (as a real team's readings are).
class TeamSimulator {
 public:
  /// Throws gridloc::Error for bad sensing options.
  TeamSimulator(const TeamWorld& world, TeamSensing sensing);
  explicit TeamSimulator(TeamCandidates candidates);

  /// Each robot's sensing at `poses` and the links they can measure (noise from `seed`).
  TeamCase simulate(const std::vector<Pose2>& poses, std::uint64_t seed) const;
  /// TeamCandidates::from_scan.
  TeamRobot robot_from_scan(const RangeScan& scan, std::vector<ScanFeature>* features) const {
    return candidates_.from_scan(scan, features);
  }
  /// TeamCandidates::from_sonar.
  TeamRobot robot_from_sonar(const std::vector<double>& ranges) const {
    return candidates_.from_sonar(ranges);
  }

  const TeamCandidates& candidates() const { return candidates_; }
  const TeamWorld& world() const { return candidates_.world(); }
  const TeamSensing& sensing() const { return candidates_.sensing(); }

 private:
  TeamCandidates candidates_;
};

struct TeamProtocolOptions {
  std::vector<int> robots = {1, 2, 3, 4};  ///< team sizes, one configuration each
  int trials = 100;                        ///< per team size
  std::uint64_t seed = 1;
  /// A robot stands at least this far from every wall and from the others (m).
  double clearance_m = 0.08;
  /// Correct: every robot within these of its truth (m, rad).
  double correct_m = 0.10;
  double correct_theta = 0.0872664625997;  ///< 5 deg
  int draw_attempts = 5000;                ///< per robot, before the trial is given up
  TeamOptions team;
};

/// Checks the options; throws gridloc::Error naming the field.
void validate(const TeamProtocolOptions& options);

/// A random team of `count`: the first robot uniform over the free space, each next one within
/// the camera's range of an earlier one with a line of sight, every robot clear of the walls
/// and the others and (IR) seeing a corner or wall. Throws gridloc::Error when the attempts
/// run out.
std::vector<Pose2> draw_team(const TeamSimulator& simulator, int count,
                             const TeamProtocolOptions& options, std::uint64_t seed);

struct TeamConfiguration {
  int robots = 0;
  int trials = 0;
  double unique_correct_rate = 0.0;  ///< localized, every robot correct
  double ambiguous_rate = 0.0;
  double not_localized_rate = 0.0;
  int wrong_localized = 0;  ///< localized with a robot not correct
  /// Over the localized trials' robots.
  double mean_position_error_m = 0.0;
  double mean_heading_error_deg = 0.0;
  double median_ms = 0.0;  ///< features, candidates and the team solve, per trial
};

/// How a team's answer compares with its truth.
struct TeamOutcome {
  Verdict verdict = Verdict::NotLocalized;
  bool correct = false;
  double max_position_error_m = 0.0, max_heading_error = 0.0;  ///< of the best solution
};
TeamOutcome judge(const TeamAnswer& answer, const std::vector<Pose2>& truth,
                  const TeamProtocolOptions& options);

struct TeamProtocolReport {
  std::vector<TeamConfiguration> overall;                 ///< per team size, over every world
  std::vector<std::vector<TeamConfiguration>> per_world;  ///< [world][team size]
};

/// The protocol: options.trials random teams per size on each world (the same seeds on
/// each); `progress` (may be empty) after each trial with (trials done, trials in all).
TeamProtocolReport run_team_protocol(const std::vector<const TeamSimulator*>& worlds,
                                     const TeamProtocolOptions& options,
                                     const std::function<void(int, int)>& progress = {});

}  // namespace gridloc
