// Tests of engine/src/evaluation/drive_protocol.cpp: the drive protocol compares the fused
// drive with the last firing alone on the same trials.
#include "gridloc/engine/evaluation/drive_protocol.hpp"

#include <gtest/gtest.h>

#include "gridloc/grids/map_io.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

const SonarRing& ring() {
  static const SonarRing loaded = load_sonar_ring(test::ring_path());
  return loaded;
}

TEST(DriveProtocol, ADriveLocalizesAtLeastAsOftenAsTheLastFiring) {
  // Measured (gridloc eval --drive 2, seed 1, 100 trials per room, global): see
  // engine/doc/correlation.md; 10 trials per room keep the ordering with a margin.
  std::vector<EvalMap> maps;
  for (const char* name : {"room_rect", "room_l"}) {
    maps.push_back({name, load_ros_map(test::map_path(name))});
  }
  DriveEvalOptions options;
  options.trials = 10;
  const DriveEvalReport report = run_drive_evaluation(maps, ring(), options);
  ASSERT_EQ(report.maps.size(), 2u);
  for (const DriveEvalRow& row : report.maps) {
    EXPECT_EQ(row.trials, 10);
    EXPECT_EQ(row.drive.localized + row.drive.ambiguous + row.drive.not_localized, 10);
    EXPECT_GE(row.drive.successes, 9) << row.map;
    EXPECT_GE(row.drive.localized, row.standstill.localized - 1) << row.map;
    EXPECT_EQ(row.drive.confident_wrong, 0) << row.map;
  }
  // The same seed gives the same trials and answers.
  const DriveEvalReport again = run_drive_evaluation(maps, ring(), options);
  EXPECT_EQ(again.maps[1].drive.successes, report.maps[1].drive.successes);
  EXPECT_EQ(again.maps[1].standstill.localized, report.maps[1].standstill.localized);
}

TEST(DriveProtocol, BadOptionsAreNamed) {
  const std::vector<EvalMap> maps = {{"room_rect", load_ros_map(test::map_path("room_rect"))}};
  DriveEvalOptions options;
  options.firings = 1;
  test::expect_error([&] { run_drive_evaluation(maps, ring(), options); }, {"firings"});
  options = {};
  options.drive_m = -1.0;
  test::expect_error([&] { run_drive_evaluation(maps, ring(), options); }, {"drive_m"});
  options = {};
  options.drive_m = 15.0;  // no straight free path that long in a 6 m room
  options.trials = 1;
  test::expect_error([&] { run_drive_evaluation(maps, ring(), options); },
                     {"no free straight path"});
}

}  // namespace
}  // namespace gridloc
