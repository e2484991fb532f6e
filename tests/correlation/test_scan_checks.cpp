// Tests of check_scan_answer: a laser scan's answer that shoots its beams through the map's
// walls, or whose winner lies on its window's edge, is not localized, one with a second place
// nearly as good ambiguous; its pose stays, and an answer that was not localized keeps its
// verdict.
#include "gridloc/engine/correlation/scan_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.hpp"
#include "walled_room.hpp"

namespace gridloc {
namespace {

OccupancyMap room() {
  return test::walled_room();
}

/// Four beams (east, north, west, south) seen from the room's centre: every wall 1.95 m away.
RangeScan centre_scan() {
  RangeScan scan;
  scan.max_range = 8.0;
  scan.angles = {0.0, 0.5 * std::numbers::pi, std::numbers::pi, 1.5 * std::numbers::pi};
  scan.ranges = {1.95, 1.95, 1.95, 1.95};
  return scan;
}

Estimate localized_at(const Pose2& pose, double fit) {
  Estimate estimate;
  estimate.pose = pose;
  estimate.normalized_score = fit;
  estimate.verdict = Verdict::Localized;
  return estimate;
}

TEST(ScanChecks, AnAnswerThroughWallsIsNotLocalizedAndKeepsItsPose) {
  // 1 m east of the truth the east beam crosses the east wall: a quarter of the returns.
  Estimate wrong = localized_at({4.0, 3.0, 0.0}, 0.3);
  check_scan_answer(wrong, room(), centre_scan(), ScanChecks{});
  EXPECT_DOUBLE_EQ(wrong.through_walls, 0.25);
  EXPECT_EQ(wrong.verdict, Verdict::NotLocalized);  // 0.25 >= 0.7 * 0.3
  EXPECT_DOUBLE_EQ(wrong.pose.x, 4.0);
  // A fit twice as good outweighs the same share (0.25 < 0.7 * 0.6).
  Estimate fitting = localized_at({4.0, 3.0, 0.0}, 0.6);
  check_scan_answer(fitting, room(), centre_scan(), ScanChecks{});
  EXPECT_EQ(fitting.verdict, Verdict::Localized);
  Estimate right = localized_at({3.0, 3.0, 0.0}, 0.3);
  check_scan_answer(right, room(), centre_scan(), ScanChecks{});
  EXPECT_DOUBLE_EQ(right.through_walls, 0.0);
  EXPECT_EQ(right.verdict, Verdict::Localized);
}

TEST(ScanChecks, AWinnerOnTheWindowsEdgeIsNotLocalizedUnlessAskedOtherwise) {
  Estimate edge = localized_at({3.0, 3.0, 0.0}, 0.9);
  edge.on_window_edge = true;
  Estimate kept = edge;
  check_scan_answer(edge, room(), centre_scan(), ScanChecks{});
  EXPECT_EQ(edge.verdict, Verdict::NotLocalized);
  ScanChecks no_edge;
  no_edge.edge_not_localized = false;
  check_scan_answer(kept, room(), centre_scan(), no_edge);
  EXPECT_EQ(kept.verdict, Verdict::Localized);
}

TEST(ScanChecks, NoWallCheckAtZeroAndOtherVerdictsStay) {
  ScanChecks unchecked;
  unchecked.through_wall_ratio = 0.0;
  Estimate wrong = localized_at({4.0, 3.0, 0.0}, 0.3);
  check_scan_answer(wrong, room(), centre_scan(), unchecked);
  EXPECT_TRUE(std::isnan(wrong.through_walls));
  EXPECT_EQ(wrong.verdict, Verdict::Localized);
  Estimate ambiguous = localized_at({4.0, 3.0, 0.0}, 0.3);
  ambiguous.verdict = Verdict::Ambiguous;
  ambiguous.on_window_edge = true;
  check_scan_answer(ambiguous, room(), centre_scan(), ScanChecks{});
  EXPECT_EQ(ambiguous.verdict, Verdict::Ambiguous);
  EXPECT_DOUBLE_EQ(ambiguous.through_walls, 0.25);  // still reported
}

// Issue 19: a windowed answer with a second place nearly as good, farther than 0.3 m, while
// some of its returns cross walls and its confidence is moderate, is `ambiguous`; take away
// any one of the four and it stays `localized`.
TEST(ScanChecks, ASecondPlaceNearlyAsGoodMakesAnUncleanAnswerAmbiguous) {
  // Half a metre east of the truth the east beam crosses the wall: a quarter of the returns,
  // below the through-walls check at this fit (0.25 < 0.7 * 0.6).
  const auto answer = [](double confidence, double second_score, double second_x) {
    Estimate estimate = localized_at({3.5, 3.0, 0.0}, 0.6);
    estimate.score = 100.0;
    estimate.confidence = confidence;
    estimate.alternatives = {{{3.5, 3.0, 0.0}, 100.0}, {{second_x, 3.0, 0.0}, second_score}};
    return estimate;
  };
  Estimate slid = answer(0.3, 90.0, 3.0);
  check_scan_answer(slid, room(), centre_scan(), ScanChecks{});
  EXPECT_DOUBLE_EQ(slid.through_walls, 0.25);
  EXPECT_EQ(slid.verdict, Verdict::Ambiguous);
  EXPECT_TRUE(slid.ambiguous);
  EXPECT_DOUBLE_EQ(slid.pose.x, 3.5);
  for (Estimate kept : {answer(0.6, 90.0, 3.0),     // confident
                        answer(0.3, 85.0, 3.0),     // the second place scores less
                        answer(0.3, 90.0, 3.3)}) {  // the second place is near
    check_scan_answer(kept, room(), centre_scan(), ScanChecks{});
    EXPECT_EQ(kept.verdict, Verdict::Localized) << kept.confidence;
  }
  Estimate clean = answer(0.3, 90.0, 3.5);  // at the truth, the second place 0.5 m west
  clean.pose = clean.alternatives.front().pose = {3.0, 3.0, 0.0};
  check_scan_answer(clean, room(), centre_scan(), ScanChecks{});
  EXPECT_DOUBLE_EQ(clean.through_walls, 0.0);
  EXPECT_EQ(clean.verdict, Verdict::Localized);
  ScanChecks off;
  off.close_second_ratio = 0.0;
  Estimate unchecked = answer(0.3, 90.0, 3.0);
  check_scan_answer(unchecked, room(), centre_scan(), off);
  EXPECT_EQ(unchecked.verdict, Verdict::Localized);
  // It reads the wall check's share: without the wall check it never fires.
  ScanChecks no_walls;
  no_walls.through_wall_ratio = 0.0;
  Estimate unread = answer(0.3, 90.0, 3.0);
  check_scan_answer(unread, room(), centre_scan(), no_walls);
  EXPECT_EQ(unread.verdict, Verdict::Localized);
}

TEST(ScanChecks, BadChecksAreNamed) {
  Estimate estimate = localized_at({3.0, 3.0, 0.0}, 0.5);
  ScanChecks checks;
  checks.through_wall_ratio = -0.1;
  test::expect_error([&] { check_scan_answer(estimate, room(), centre_scan(), checks); },
                     {"through_wall_ratio", "-0.1"});
  checks = ScanChecks{};
  checks.through_wall_margin_m = std::nan("");
  test::expect_error([&] { check_scan_answer(estimate, room(), centre_scan(), checks); },
                     {"through_wall_margin_m"});
  checks = ScanChecks{};
  checks.close_second_ratio = 1.5;
  test::expect_error([&] { check_scan_answer(estimate, room(), centre_scan(), checks); },
                     {"close_second_ratio"});
}

}  // namespace
}  // namespace gridloc
