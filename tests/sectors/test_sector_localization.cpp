// Tests of engine/src/sectors/localization.cpp (seed 000 §3): the pose from a scan's label, the
// skeleton match, look-alikes, dropouts, the covariance and the full-turn check.
#include "gridloc/engine/sectors/localization.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "gridloc/engine/evaluation/sector_protocol.hpp"
#include "gridloc/sensors/rng.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

PolygonMap l_room() {
  return make_polygon_map({{0, 0}, {7, 0}, {7, 3}, {3, 3}, {3, 6}, {0, 6}}, {});
}

TEST(SectorLocalization, RecoversThePoseAtEachSectorsCentre) {
  // Noise-free 360-beam scans (1 deg), turned by 1 rad, from the middle of each sector: the
  // label matches and the located vertices give the pose (seed 000 eqs. (2)-(9)).
  const PolygonMap m = l_room();
  const SectorMap s = compute_sectors(m);
  SectorLocalizationOptions o;
  o.label.median_window = 1;
  for (std::size_t k = 0; k < s.sectors.size(); ++k) {
    const Eigen::Vector2d p = s.sectors[k].representative;
    const Pose2 truth{p.x(), p.y(), 1.0};
    const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 20.0), o);
    ASSERT_TRUE(f.found) << "sector " << k << " label " << f.scan_label;
    EXPECT_LT(std::hypot(f.pose.x - truth.x, f.pose.y - truth.y), 0.02) << "sector " << k;
    EXPECT_LT(std::abs(normalize_angle(f.pose.theta - truth.theta)), deg2rad(0.5)) << k;
    EXPECT_GE(f.matched_m, 2);
    EXPECT_LT(f.residual_m, 0.01);
  }
}

TEST(SectorLocalization, MostRandomPosesOfTheLRoom) {
  // 60 random poses at least 0.3 m from the walls, any heading, noise-free 360-beam scans.
  // Measured over 200 such poses: 97.0 % within 2 cm and 0.5 deg, 3 % not found, none wrong
  // (92.5 % and 7.5 % without the skeleton match); 59 of these 60.
  const PolygonMap m = l_room();
  const SectorMap s = compute_sectors(m);
  SectorLocalizationOptions o;
  o.label.median_window = 1;
  Rng rng(3);
  int tried = 0, good = 0;
  while (tried < 60) {
    const Pose2 truth{rng.uniform(0.3, 6.7), rng.uniform(0.3, 5.7), rng.uniform(-3.1, 3.1)};
    // Outside the L, or within 0.3 m of its inner walls.
    if (truth.x > 2.7 && truth.y > 2.7) continue;
    ++tried;
    const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 20.0), o);
    good += f.found && std::hypot(f.pose.x - truth.x, f.pose.y - truth.y) < 0.02 &&
                    std::abs(normalize_angle(f.pose.theta - truth.theta)) < deg2rad(0.5)
                ? 1
                : 0;
  }
  std::cout << "[sectors] L room: " << good << "/60 within 2 cm and 0.5 deg\n";
  EXPECT_GE(good, 56);
}

TEST(SectorLocalization, TheSkeletonMatchLocalizesPartialViews) {
  // The bundled office seen by 360 beams: far and short edges get too few readings for their
  // extrema (seed 000's assumption (ii)), so exact labels often differ from the sectors'. The
  // D c skeleton still matches. Measured on these 12 poses: 6 within 2 cm and 0.5 deg without
  // it, 12 with it (with the look-alike search on in both).
  const PolygonMap m = load_polygon_map(test::maps_dir() + "/polygons/office.yaml");
  const SectorMap s = compute_sectors(m);
  const auto good = [&](bool skeleton) {
    SectorLocalizationOptions o;
    o.label.median_window = 1;
    o.skeleton_matching = skeleton;
    Rng rng(5);
    int n = 0;
    for (int t = 0; t < 12; ++t) {
      const Pose2 truth = sample_polygon_pose(m, 0.3, rng);
      const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 30.0), o);
      n += f.found && std::hypot(f.pose.x - truth.x, f.pose.y - truth.y) < 0.02 &&
                   std::abs(normalize_angle(f.pose.theta - truth.theta)) < deg2rad(0.5)
               ? 1
               : 0;
    }
    return n;
  };
  const int without = good(false), with = good(true);
  std::cout << "[sectors] office: " << without << "/12 without the skeleton match, " << with
            << "/12 with it\n";
  EXPECT_GE(with, 11);
  EXPECT_GT(with, without);
}

TEST(SectorLocalization, ASymmetricRoomIsAmbiguousNotWrong) {
  // A room that is itself turned by 180 deg about (4, 2): every scan has a twin pose. The fix
  // must say so (seed 000 §4.1) rather than pick one.
  const PolygonMap m = make_polygon_map(
      {{0, 0}, {8, 0}, {8, 4}, {0, 4}},
      {{{2, 0.8}, {3, 0.8}, {3, 1.8}, {2, 1.8}}, {{5, 2.2}, {6, 2.2}, {6, 3.2}, {5, 3.2}}});
  const SectorMap s = compute_sectors(m);
  int shared = 0;
  for (const Sector& sector : s.sectors) shared += sector.ambiguous ? 1 : 0;
  EXPECT_GT(shared, 0);
  Rng rng(2);
  int found = 0;
  for (int t = 0; t < 8; ++t) {
    const Pose2 truth = sample_polygon_pose(m, 0.3, rng);
    const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 30.0));
    if (!f.found) continue;
    ++found;
    EXPECT_TRUE(f.ambiguous) << "trial " << t;
  }
  EXPECT_GE(found, 6);
}

TEST(SectorLocalization, TheLookAlikeSearchFindsTheTwinALabelMisses) {
  // The bundled symmetric room: its twin sectors' labels, read at points that are not twins,
  // differ here and there, so the label match alone sometimes finds only one of the two poses
  // and answers it. Placing the located vertices on every look-alike vertex pair finds the
  // other. Measured on these 30 poses: 3 answered without the search, none with it.
  const PolygonMap m = load_polygon_map(test::maps_dir() + "/polygons/room_symmetric.yaml");
  const SectorMap s = compute_sectors(m);
  const auto answered = [&](bool search) {
    SectorLocalizationOptions o;
    o.lookalike_search = search;
    Rng rng(8);
    int n = 0, found = 0;
    for (int t = 0; t < 30; ++t) {
      const Pose2 truth = sample_polygon_pose(m, 0.3, rng);
      const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 8.0), o);
      found += f.found ? 1 : 0;
      n += f.found && !f.ambiguous ? 1 : 0;
    }
    EXPECT_GE(found, 28);
    return n;
  };
  const int without = answered(false), with = answered(true);
  std::cout << "[sectors] symmetric room: " << without << "/30 answered without the look-alike "
            << "search, " << with << "/30 with it\n";
  EXPECT_EQ(with, 0);
  EXPECT_GT(without, 0);
}

TEST(SectorLocalization, TwinsFoundFromAnyWinner) {
  // Review cases in the symmetric room: a twin the look-alike search must reach even when the
  // winner's rough pose is refuted before its polish, or when one of its located corners is a
  // wall point that lands on no vertex. Both were answered "localized" (and one wrongly).
  const PolygonMap m = load_polygon_map(test::maps_dir() + "/polygons/room_symmetric.yaml");
  const SectorMap s = compute_sectors(m);
  for (const Pose2& truth : {Pose2{0.8, 2.196, -3.04}, Pose2{5.143, 1.325, -0.927}}) {
    const SectorFix f = localize_in_sectors(s, polygon_scan(m, truth, 360, 8.0));
    ASSERT_TRUE(f.found);
    EXPECT_TRUE(f.ambiguous) << truth.x << ", " << truth.y;
    ASSERT_EQ(f.alternatives.size(), 2u);
    // One of the two is the truth, the other its turn about (3.15, 2.15).
    const Pose2 twin{6.3 - truth.x, 4.3 - truth.y, normalize_angle(truth.theta + std::numbers::pi)};
    for (const Pose2& p : {truth, twin}) {
      EXPECT_TRUE(std::any_of(f.alternatives.begin(), f.alternatives.end(),
                              [&](const auto& a) {
                                return std::hypot(a.pose.x - p.x, a.pose.y - p.y) < 0.02 &&
                                       std::abs(normalize_angle(a.pose.theta - p.theta)) < 0.01;
                              }))
          << p.x << ", " << p.y;
    }
  }
}

TEST(SectorLocalization, DropoutsAreBridged) {
  // Six gaps of two beams without return (glass, a dark surface) on walls of the L room: each
  // used to add a D c D c to the label and leave no sector to match.
  const PolygonMap m = l_room();
  const SectorMap s = compute_sectors(m);
  const Pose2 truth{1.5, 1.5, 0.3};
  RangeScan scan = polygon_scan(m, truth, 360, 20.0);
  for (int start : {20, 80, 140, 200, 260, 320}) scan.ranges[start] = scan.ranges[start + 1] = 20.0;
  const SectorFix f = localize_in_sectors(s, scan);
  ASSERT_TRUE(f.found) << f.scan_label;
  EXPECT_LT(std::hypot(f.pose.x - truth.x, f.pose.y - truth.y), 0.02);
  EXPECT_FALSE(f.ambiguous);
  // A real opening (a long run of no return) is still a view into the distance.
  ScanLabelOptions bridge;
  bridge.bridge_beams = 3;
  RangeScan open = polygon_scan(m, truth, 360, 20.0);
  for (int k = 100; k < 110; ++k) open.ranges[k] = 20.0;
  const std::string label = construct_scan_label(open, bridge).label;
  EXPECT_GE(std::count(label.begin(), label.end(), 'D'), 2) << label;
}

TEST(SectorLocalization, ThePoseHasACovariance) {
  const PolygonMap m = l_room();
  const SectorMap s = compute_sectors(m);
  const SectorFix f = localize_in_sectors(s, polygon_scan(m, {1.5, 1.5, 0.3}, 360, 20.0));
  ASSERT_TRUE(f.found);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(f.covariance(k, k), 0.0);
    EXPECT_LT(f.covariance(k, k), 1e-4);  // noise-free: sub-centimetre, sub-degree
  }
}

TEST(SectorLocalization, AScanMustBeAFullTurn) {
  const SectorMap s = compute_sectors(l_room());
  const RangeScan full = polygon_scan(l_room(), {1.5, 1.5, 0.3}, 360, 20.0);
  RangeScan half = full;  // a 180 deg field of view
  half.angles.resize(180);
  half.ranges.resize(180);
  test::expect_error([&] { localize_in_sectors(s, half); }, {"covers 179 deg", "360"});
  RangeScan clockwise = full;
  std::reverse(clockwise.angles.begin(), clockwise.angles.end());
  std::reverse(clockwise.ranges.begin(), clockwise.ranges.end());
  test::expect_error([&] { localize_in_sectors(s, clockwise); }, {"increase", "beam 1"});
  RangeScan degrees = full;
  for (double& a : degrees.angles) a = rad2deg(a);
  test::expect_error([&] { localize_in_sectors(s, degrees); }, {"more than a turn", "radians"});
}

TEST(SectorLocalization, AScanOfAnotherPlaceIsNotFound) {
  const SectorMap s = compute_sectors(l_room());
  // A round room of radius 2 m: no corner, no sector.
  RangeScan round;
  round.max_range = 20.0;
  for (int k = 0; k < 360; ++k) {
    round.angles.push_back(deg2rad(k));
    round.ranges.push_back(2.0);
  }
  const SectorFix f = localize_in_sectors(s, round);
  EXPECT_FALSE(f.found);
  EXPECT_EQ(f.candidates, 0);
}

}  // namespace
}  // namespace gridloc
