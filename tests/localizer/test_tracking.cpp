// Tests of the Localizer's tracking (issue 34): an ambiguous start between two identical
// rooms resolves after a drive without a wrong `localized` answer; a seeded odometry slip is
// not `localized` until the new place has held; a re-search after a loss runs in slices
// across updates and reports its progress.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/sensors/odometry_noise.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "laser_cases.hpp"
#include "test_support.hpp"
#include "tracking_cases.hpp"

namespace gridloc {
namespace {

using test::kRange;
using test::laser;
using test::laser_options;
using test::right;
using test::scan_at;
using test::two_rooms;

bool has_place_near(const Estimate& e, const Pose2& place) {
  for (const Hypothesis& h : e.alternatives) {
    if (std::hypot(h.pose.x - place.x, h.pose.y - place.y) < 0.2) return true;
  }
  return false;
}

/// From room B's middle south through its door into the corridor, then east.
std::vector<Pose2> drive_out_of_room_b() {
  std::vector<Pose2> path;
  for (double y = 5.5; y > 3.0; y -= 0.1) path.push_back({10.0, y, -0.5 * std::numbers::pi});
  for (double x = 10.0; x < 12.0; x += 0.1) path.push_back({x, 3.0, 0.0});
  return path;
}

/// East through room B, south out of its door, east along the corridor.
std::vector<Pose2> through_room_b_to_the_corridor() {
  std::vector<Pose2> path;
  for (double x = 8.0; x < 10.0; x += 0.1) path.push_back({x, 5.5, 0.0});
  for (double y = 5.5; y > 3.0; y -= 0.1) path.push_back({10.0, y, -0.5 * std::numbers::pi});
  for (double x = 10.0; x < 14.0; x += 0.1) path.push_back({x, 3.0, 0.0});
  return path;
}

TEST(Tracking, TwoIdenticalRoomsResolveAfterADriveWithoutAWrongAnswer) {
  const OccupancyMap map = two_rooms();
  Localizer localizer(map, laser(), laser_options());
  const std::vector<Pose2> path = drive_out_of_room_b();
  int localized_right = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    localizer.add_odometry(path[k]);  // exact odometry: only the views tell the rooms apart
    localizer.add_observation(double(k), scan_at(map, path[k]));
    const Estimate e = localizer.estimate();
    if (k == 0) {
      EXPECT_EQ(e.verdict, Verdict::Ambiguous);
      EXPECT_TRUE(has_place_near(e, path[0]));
      EXPECT_TRUE(has_place_near(e, {path[0].x - 6.0, path[0].y, path[0].theta}));  // room A
    }
    if (e.verdict == Verdict::Localized) {
      EXPECT_TRUE(right(e, path[k])) << "a wrong localized answer at step " << k;
      ++localized_right;
    }
  }
  EXPECT_EQ(localizer.estimate().verdict, Verdict::Localized);
  EXPECT_GE(localized_right, 5);
}

TEST(Tracking, ASeededSlipIsNotLocalizedUntilTheTrackHasHeld) {
  const OccupancyMap map = two_rooms();
  Localizer localizer(map, laser(), laser_options());
  const std::vector<Pose2> path = through_room_b_to_the_corridor();
  OdometryNoise noise;
  noise.frac = 0.0;
  noise.rad_per_m = 0.0;
  noise.slip_every_m = 3.0;  // a 0.3 m / 10 deg slip about every 3 m
  Rng rng(5);
  const std::vector<Pose2> odometry = drifting_odometry(path, noise, rng);
  localizer.add_odometry(odometry[0]);
  localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
  int rejected = 0, localized = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    localizer.add_odometry(odometry[k]);
    localizer.add_observation(double(k), scan_at(map, path[k]));
    const Estimate e = localizer.estimate();
    const LocalizerStatus status = localizer.status();
    rejected += status.jump_rejected;
    // Every answer held back names why, and the gate's refusals say so.
    EXPECT_EQ(e.verdict == Verdict::NotLocalized, status.held_back != HeldBack::None) << k;
    if (status.jump_rejected) {
      EXPECT_EQ(status.held_back, HeldBack::JumpRejected) << to_string(status.held_back);
    }
    if (e.verdict != Verdict::Localized) continue;
    ++localized;
    EXPECT_LE(std::hypot(e.pose.x - path[k].x, e.pose.y - path[k].y), 0.1) << "step " << k;
    EXPECT_LE(std::abs(normalize_angle(e.pose.theta - path[k].theta)), deg2rad(2.0)) << k;
  }
  // The odometry slipped (the seed puts two slips within the 9 m drive), the gate saw it,
  // and the track was localized again within a metre or so each time.
  const Pose2 without_slips = compose(odometry.front(), relative_pose(path.front(), path.back()));
  const Pose2 off = relative_pose(odometry.back(), without_slips);
  ASSERT_GT(std::hypot(off.x, off.y), 0.2);
  EXPECT_GE(rejected, 2);
  EXPECT_GE(localized, static_cast<int>(path.size()) * 2 / 3);
  EXPECT_TRUE(right(localizer.estimate(), path.back()));
}

// With its whole-map searches on the coarse copy, a laser tracker builds its own grids only
// as deep as its widest window (max_half_xy_m) needs (issue 17: less precomputation and
// memory); from no prior, through slips and the re-searches they start, every answer is the
// one a tracker with grids as deep as the map gives.
TEST(Tracking, TheTrackersGridsOnlyAsDeepAsItsWidestWindowChangeNoAnswer) {
  const OccupancyMap map = two_rooms();
  LocalizerOptions deep_options = laser_options();
  deep_options.correlation.max_bound_depth = 31;  // as deep as the map
  Localizer shallow(map, laser(), laser_options()), deep(map, laser(), deep_options);
  SearchWindow widest;
  widest.half_xy = laser_options().max_half_xy_m;
  widest.step_xy = 0.05;
  EXPECT_EQ(shallow.estimator().options().max_bound_depth, window_bound_depth(widest));
  EXPECT_EQ(deep.estimator().options().max_bound_depth, 31);
  LocalizerOptions exact_first = laser_options();
  exact_first.research.coarse_first_search = false;  // a whole-map search on its own grids
  EXPECT_EQ(Localizer(map, laser(), exact_first).estimator().options().max_bound_depth, 0);
  const std::vector<Pose2> path = through_room_b_to_the_corridor();
  OdometryNoise noise;
  noise.slip_every_m = 2.0;
  Rng rng(7);
  const std::vector<Pose2> odometry = drifting_odometry(path, noise, rng);
  for (std::size_t k = 0; k < path.size(); ++k) {
    for (Localizer* localizer : {&shallow, &deep}) {
      localizer->add_odometry(odometry[k]);
      localizer->add_observation(double(k), scan_at(map, path[k]));
    }
    const Estimate a = shallow.estimate(), b = deep.estimate();
    EXPECT_EQ(a.verdict, b.verdict) << k;
    EXPECT_EQ(a.pose.x, b.pose.x) << k;
    EXPECT_EQ(a.pose.y, b.pose.y) << k;
    EXPECT_EQ(a.pose.theta, b.pose.theta) << k;
    EXPECT_EQ(a.alternatives.size(), b.alternatives.size()) << k;
  }
}

// LocalizerOptions::localized_fit_ratio: a scan half hidden by people fits the tracked place
// far worse than the scans before it; with the rule it is not `localized` (the place still
// follows the window), without it the window's own verdict stands.
TEST(Tracking, AScanFittingFarWorseThanUsualIsNotLocalizedUnderTheFitRule) {
  const OccupancyMap map = two_rooms();
  for (const double ratio : {0.0, 0.8}) {
    LocalizerOptions options = laser_options();
    options.localized_fit_ratio = ratio;
    Localizer localizer(map, laser(), options);
    std::vector<Pose2> path;  // east through room B
    for (double x = 8.0; x < 10.5; x += 0.1) path.push_back({x, 5.5, 0.0});
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    const std::size_t hidden = path.size() - 1;
    for (std::size_t k = 0; k < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      RangeScan scan = scan_at(map, path[k]);
      if (k == hidden) {  // people 0.4 m away in front of 40 % of the beams
        for (std::size_t i = 0; i < scan.ranges.size(); i += 5) {
          scan.ranges[i] = scan.ranges[i + 1] = 0.4;
        }
      }
      localizer.add_observation(double(k), scan);
      const Estimate e = localizer.estimate();
      if (k + 1 == hidden) {
        ASSERT_EQ(e.verdict, Verdict::Localized) << "ratio " << ratio;
      }
      if (k == hidden) {
        EXPECT_EQ(e.verdict, ratio > 0.0 ? Verdict::NotLocalized : Verdict::Localized)
            << "ratio " << ratio;
        EXPECT_EQ(localizer.status().held_back, ratio > 0.0 ? HeldBack::WeakFit : HeldBack::None)
            << to_string(localizer.status().held_back);
        EXPECT_LE(std::hypot(e.pose.x - path[k].x, e.pose.y - path[k].y), 0.1) << ratio;
      }
    }
  }
  LocalizerOptions bad = laser_options();
  bad.localized_fit_ratio = 1.5;
  EXPECT_THROW(Localizer(map, laser(), bad), Error);
}

// LocalizerOptions::weak_fit_ratio: people stand 1.2 m away before 80 % of the beams for six
// scans while the odometry overruns by 30 %. Each such scan fits the place at under half its usual
// score (a miss), yet its winner is tight and lies where the odometry put the place: with
// the rule it still places the place, `localized` and right; without it the place rides on
// the odometry, not `localized`.
TEST(Tracking, ARoomChangedSinceTheMapStillPlacesThePlace) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 10.55; x += 0.1) path.push_back({x, 5.5, 0.0});
  const std::size_t first_hidden = path.size() - 6;
  for (const double ratio : {LocalizerOptions{}.weak_fit_ratio, 0.5}) {
    LocalizerOptions options = laser_options();
    options.weak_fit_ratio = ratio;
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    Pose2 odometry = path[0];
    for (std::size_t k = 0; k < path.size(); ++k) {
      const bool hidden = k >= first_hidden;
      if (k > 0) {
        const Pose2 step = relative_pose(path[k - 1], path[k]);
        odometry = compose(odometry, {step.x * (hidden ? 1.3 : 1.0), step.y, step.theta});
      }
      localizer.add_odometry(odometry);
      RangeScan scan = scan_at(map, path[k]);
      for (std::size_t i = 0; hidden && i + 3 < scan.ranges.size(); i += 5) {
        scan.ranges[i] = scan.ranges[i + 1] = scan.ranges[i + 2] = scan.ranges[i + 3] = 1.2;
      }
      localizer.add_observation(double(k), scan);
      const Estimate e = localizer.estimate();
      if (!hidden) {
        ASSERT_TRUE(right(e, path[k])) << "ratio " << ratio << " step " << k;
        ASSERT_EQ(e.verdict, Verdict::Localized) << "ratio " << ratio << " step " << k;
      } else if (ratio < options.miss_fit_ratio) {
        EXPECT_TRUE(right(e, path[k])) << "step " << k;
        EXPECT_EQ(e.verdict, Verdict::Localized) << "step " << k;
      } else {
        EXPECT_NE(e.verdict, Verdict::Localized) << "step " << k;
      }
    }
  }
  LocalizerOptions bad = laser_options();
  bad.weak_fit_ratio = -0.1;
  EXPECT_THROW(Localizer(map, laser(), bad), Error);
  bad = laser_options();
  bad.turn_fit_ratio = 1.5;  // the rule itself: TrackRealLog in tests/cli/test_track_cli.cpp
  test::expect_error([&] { Localizer(map, laser(), bad); }, {"turn_fit_ratio", "1.5"});
}

// LocalizerOptions::split_far_winners: for three scans the laser sees what it would see
// 0.5 m further east (a view the map's half saw differently), the odometry exact. Split,
// the window's winner joins as a place of its own, weighted by the odometry's prior (here
// far too unlikely to stay), and the track stays by the odometry's pose; followed, the
// place moves 0.5 m at once. Neither is `localized` off, and both are right again after.
TEST(Tracking, AFarWinnerJoinsAsAPlaceRatherThanMovingTheTrack) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 10.05; x += 0.1) path.push_back({x, 5.5, 0.0});
  const std::size_t first_shifted = 8, after_shifted = 11;
  for (const bool split : {true, false}) {
    LocalizerOptions options = laser_options();
    options.split_far_winners = split;
    options.min_half_xy_m = 1.0;  // every window sees the place 0.5 m away
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    for (std::size_t k = 0; k < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      const bool shifted = k >= first_shifted && k < after_shifted;
      const Pose2 seen = shifted ? Pose2{path[k].x + 0.5, path[k].y, 0.0} : path[k];
      localizer.add_observation(double(k), scan_at(map, seen));
      const Estimate e = localizer.estimate();
      const double off = std::hypot(e.pose.x - path[k].x, e.pose.y - path[k].y);
      if (e.verdict == Verdict::Localized) {
        EXPECT_LE(off, 0.1) << split << " step " << k;
      }
      if (k == first_shifted) {  // split, the track stayed; followed, the place moved
        EXPECT_TRUE(split ? off <= 0.2 : off >= 0.4) << split << ": " << off << " m off";
        if (split) {
          EXPECT_EQ(localizer.status().held_back, HeldBack::SplitOff)
              << to_string(localizer.status().held_back);
        }
      }
    }
    EXPECT_TRUE(right(localizer.estimate(), path.back())) << split;
    EXPECT_EQ(localizer.estimate().verdict, Verdict::Localized) << split;
  }
}

// LocalizerOptions::kept_heading_sigmas: as above, but the odometry also turns 6 degrees the
// robot did not at the first shifted scan (its model doubts about 3 degrees a step). The
// winner 0.5 m away splits off; the place the odometry carried stays, looked for within two
// standard deviations of its heading, so it is kept at the true heading; near the carried
// heading alone (0) it is kept 3 degrees off, where the scan fits it far worse.
TEST(Tracking, APlaceKeptBesideASplitOffWinnerIsKeptAtItsBestHeading) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 10.05; x += 0.1) path.push_back({x, 5.5, 0.0});
  const std::size_t first_shifted = 8, after_shifted = 11;
  const double extra_turn = deg2rad(6.0);
  for (const double sigmas : {LocalizerOptions{}.kept_heading_sigmas, 0.0}) {
    LocalizerOptions options = laser_options();
    options.kept_heading_sigmas = sigmas;
    options.min_half_xy_m = 1.0;                        // every window sees the place 0.5 m away
    options.odometry_turn_error_per_m = deg2rad(30.0);  // 3 deg of doubt a step
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    for (std::size_t k = 0; k < path.size(); ++k) {
      const double turned = k >= first_shifted ? extra_turn : 0.0;
      localizer.add_odometry({path[k].x, path[k].y, turned});
      const bool shifted = k >= first_shifted && k < after_shifted;
      const Pose2 seen = shifted ? Pose2{path[k].x + 0.5, path[k].y, 0.0} : path[k];
      localizer.add_observation(double(k), scan_at(map, seen));
      const Estimate e = localizer.estimate();
      if (e.verdict == Verdict::Localized) {
        EXPECT_TRUE(right(e, path[k]) || sigmas == 0.0) << sigmas << " step " << k;
      }
      if (k != first_shifted) continue;
      const auto kept =
          std::find_if(e.alternatives.begin(), e.alternatives.end(), [&](const Hypothesis& h) {
            return std::hypot(h.pose.x - path[k].x, h.pose.y - path[k].y) <= 0.2;
          });
      ASSERT_NE(kept, e.alternatives.end()) << sigmas;
      const double heading_off = std::abs(rad2deg(normalize_angle(kept->pose.theta)));
      if (sigmas > 0.0) {
        EXPECT_LE(heading_off, 1.0);
      } else {
        EXPECT_GE(heading_off, 2.5);
      }
    }
    if (sigmas > 0.0) {
      EXPECT_TRUE(right(localizer.estimate(), path.back()));
      EXPECT_EQ(localizer.estimate().verdict, Verdict::Localized);
    }
  }
  LocalizerOptions bad = laser_options();
  bad.kept_max_half_theta = 4.0;
  test::expect_error([&] { Localizer(map, laser(), bad); }, {"kept_max_half_theta", "4"});
}

// LocalizerOptions::weak_fit_ratio after a plain miss: people crowd the laser (every return
// 0.6-1.4 m away) for one scan, a miss that places nothing; on the next two, 70 % of the
// returns still see them. The first of those fits the place weakly and still places it,
// but is not `localized`: with nothing placed since, a third of the usual fit is no evidence
// for where the place now is (orebro's held-out scan 214: `localized` 0.37 m off right after
// such a miss). The second is `localized` again, as is every scan once the laser sees clear.
TEST(Tracking, AWeakFitRightAfterAMissIsNotLocalized) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 10.05; x += 0.1) path.push_back({x, 5.5, 0.0});
  const std::size_t crowded = 8, first_weak = 9, after_weak = 11;
  Localizer localizer(map, laser(), laser_options());
  localizer.add_odometry(path[0]);
  localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
  Rng rng(11);
  for (std::size_t k = 0; k < path.size(); ++k) {
    localizer.add_odometry(path[k]);
    RangeScan scan = scan_at(map, path[k]);
    const bool weak = k >= first_weak && k < after_weak;
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      if (k == crowded || (weak && i % 10 < 7)) scan.ranges[i] = rng.uniform(0.6, 1.4);
    }
    localizer.add_observation(double(k), scan);
    const Estimate e = localizer.estimate();
    const HeldBack held_back = localizer.status().held_back;
    EXPECT_TRUE(right(e, path[k])) << "step " << k;
    if (k == crowded) {
      EXPECT_EQ(held_back, HeldBack::Miss) << to_string(held_back);
    } else if (k == first_weak) {
      EXPECT_EQ(held_back, HeldBack::WeakFit) << to_string(held_back);
    } else if (k > 0) {
      EXPECT_EQ(e.verdict, Verdict::Localized) << "step " << k << ": " << to_string(held_back);
    }
  }
}

// LocalizerOptions::max_half_theta: when the odometry claims a turn the robot did not make
// and doubts its heading entirely, the place is looked for at every heading by default, and
// within the cap either way of the claimed heading with it (a corridor turned round, which
// reads the same, is left to a loss and the re-search).
TEST(Tracking, APlaceIsLookedForWithinTheHeadingCap) {
  const OccupancyMap map = two_rooms();
  std::vector<Pose2> path;  // east through room B
  for (double x = 8.0; x < 9.05; x += 0.1) path.push_back({x, 5.5, 0.0});
  for (const double cap_deg : {180.0, 60.0}) {
    LocalizerOptions options = laser_options();
    options.max_half_theta = deg2rad(cap_deg);
    options.odometry_turn_error_per_rad = 1.0;  // a turn's heading is unknown
    Localizer localizer(map, laser(), options);
    localizer.add_odometry(path[0]);
    localizer.set_prior(path[0], Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      localizer.add_observation(double(k), scan_at(map, path[k]));
      ASSERT_TRUE(right(localizer.estimate(), path[k])) << "cap " << cap_deg << " step " << k;
    }
    const Pose2 claimed{path.back().x, path.back().y, deg2rad(150.0)};  // a turn never made
    localizer.add_odometry(claimed);
    localizer.add_observation(double(path.size()), scan_at(map, path.back()));
    const Estimate e = localizer.estimate();
    if (cap_deg == 180.0) {
      EXPECT_TRUE(right(e, path.back())) << "heading " << rad2deg(e.pose.theta);
    } else {
      EXPECT_LE(std::abs(normalize_angle(e.pose.theta - claimed.theta)), deg2rad(cap_deg + 1.0));
      EXPECT_NE(e.verdict, Verdict::Localized);
    }
  }
  LocalizerOptions bad = laser_options();
  bad.max_half_theta = 0.5 * bad.min_half_theta;
  EXPECT_THROW(Localizer(map, laser(), bad), Error);
}

TEST(Tracking, AReSearchRunsInSlicesAcrossUpdates) {
  const OccupancyMap map = two_rooms();
  LocalizerOptions options = laser_options();
  options.reseed_after_m = 0.3;             // while ambiguous, search again after 0.3 m
  options.research.poses_per_slice = 2e4;   // a search of this map in many slices
  options.research.cells_per_update = 0.0;  // heading slices (not one search a budget at a time)
  options.research.slices_per_update = 2;
  Localizer localizer(map, laser(), options);
  // Ambiguous between the two rooms (the first search answers at once, in one slice)...
  Pose2 pose{8.5, 5.0, 0.0};
  localizer.add_odometry(pose);
  localizer.add_observation(0.0, scan_at(map, pose));
  ASSERT_EQ(localizer.estimate().verdict, Verdict::Ambiguous);
  EXPECT_EQ(localizer.status().search_slices, 1);
  EXPECT_TRUE(localizer.status().search_finished);
  // ...so after 0.3 m within the room a search starts again, and runs two slices an update.
  std::vector<int> done;
  int slices = 0;
  bool finished = false;
  for (int k = 1; k < 400 && !finished; ++k) {
    pose = compose(pose, {0.0, k % 40 < 20 ? 0.05 : -0.05, 0.0});  // to and fro in the room
    localizer.add_odometry(pose);
    localizer.add_observation(double(k), scan_at(map, pose));
    const LocalizerStatus status = localizer.status();
    if (status.search_slices == 0) continue;
    slices = status.search_slices;
    done.push_back(status.search_slices_done);
    finished = status.search_finished;
  }
  ASSERT_TRUE(finished);
  ASSERT_GT(slices, 4);
  for (std::size_t k = 0; k < done.size(); ++k) {
    EXPECT_EQ(done[k], std::min<int>(2 * static_cast<int>(k + 1), slices)) << k;
  }
  EXPECT_EQ(done.size(), static_cast<std::size_t>((slices + 1) / 2));
  // The places it found joined the set: both rooms are still there, the truth among them.
  const Estimate e = localizer.estimate();
  EXPECT_TRUE(has_place_near(e, pose));
  EXPECT_TRUE(has_place_near(e, {pose.x - 6.0, pose.y, pose.theta}));
}

TEST(Tracking, AReSearchRunsAsOneSearchABudgetAnUpdate) {
  const OccupancyMap map = two_rooms();
  LocalizerOptions options = laser_options();
  options.reseed_after_m = 0.3;             // while ambiguous, search again after 0.3 m
  options.research.poses_per_slice = 2e4;   // too big a search for one update...
  options.research.cells_per_update = 2e4;  // ...so it runs about this many cells an update
  options.research.drop_once_localized = false;
  Localizer localizer(map, laser(), options);
  Pose2 pose{8.5, 5.0, 0.0};
  localizer.add_odometry(pose);
  localizer.add_observation(0.0, scan_at(map, pose));
  ASSERT_EQ(localizer.estimate().verdict, Verdict::Ambiguous);
  std::vector<int> done;
  std::vector<double> progress;
  bool finished = false;
  for (int k = 1; k < 400 && !finished; ++k) {
    pose = compose(pose, {0.0, k % 40 < 20 ? 0.05 : -0.05, 0.0});  // to and fro in the room
    localizer.add_odometry(pose);
    localizer.add_observation(double(k), scan_at(map, pose));
    const LocalizerStatus status = localizer.status();
    if (status.search_slices == 0) continue;
    done.push_back(status.search_slices_done);
    progress.push_back(status.search_progress);
    finished = status.search_finished;
    // One step an update; while under way it counts one more to come.
    EXPECT_EQ(status.search_slices,
              finished ? status.search_slices_done : status.search_slices_done + 1);
  }
  ASSERT_TRUE(finished);
  ASSERT_GT(done.size(), 4u);  // it ran over several updates
  for (std::size_t k = 0; k < done.size(); ++k) {
    EXPECT_EQ(done[k], static_cast<int>(k + 1)) << k;
    if (k > 0) {
      EXPECT_GE(progress[k], progress[k - 1]) << k;
    }
  }
  EXPECT_LT(progress.front(), 1.0);
  EXPECT_EQ(progress.back(), 1.0);
  // Its places joined the set: both rooms are still there, the truth among them.
  const Estimate e = localizer.estimate();
  EXPECT_TRUE(has_place_near(e, pose));
  EXPECT_TRUE(has_place_near(e, {pose.x - 6.0, pose.y, pose.theta}));
}

// A re-search started by an ambiguity is dropped once a drive resolves it: the answer is
// `localized` on one place again, so its remaining slices would only bring places the track's
// evidence outweighs. With drop_once_localized off it runs to its end.
TEST(Tracking, AReSearchIsDroppedOnceTheTrackIsLocalizedAgain) {
  const OccupancyMap map = two_rooms();
  for (const bool drop : {true, false}) {
    LocalizerOptions options = laser_options();
    options.reseed_after_m = 0.3;             // while ambiguous, search again after 0.3 m
    options.research.poses_per_slice = 2e3;   // a search of this map in many slices
    options.research.cells_per_update = 0.0;  // heading slices
    options.research.drop_once_localized = drop;
    Localizer localizer(map, laser(), options);
    // Ambiguous in room B, then 0.3 m on (a re-search starts), then out of the room.
    std::vector<Pose2> path;
    for (double y = 5.0; y <= 5.7; y += 0.1) path.push_back({10.0, y, -0.5 * std::numbers::pi});
    for (const Pose2& p : drive_out_of_room_b()) path.push_back(p);
    bool started = false, localized_during_search = false, under_way_after = false;
    for (std::size_t k = 0; k < path.size(); ++k) {
      localizer.add_odometry(path[k]);
      localizer.add_observation(double(k), scan_at(map, path[k]));
      const LocalizerStatus status = localizer.status();
      const bool under_way = status.search_slices > 0 && !status.search_finished;
      if (k > 0 && under_way) started = true;
      if (started && localized_during_search) under_way_after |= under_way;
      const Estimate e = localizer.estimate();
      if (started && e.verdict == Verdict::Localized && e.alternatives.size() == 1) {
        localized_during_search = true;
      }
    }
    ASSERT_TRUE(started) << drop;
    ASSERT_TRUE(localized_during_search) << drop;
    EXPECT_EQ(under_way_after, !drop) << drop;
    EXPECT_TRUE(right(localizer.estimate(), path.back())) << drop;
  }
}

}  // namespace
}  // namespace gridloc
