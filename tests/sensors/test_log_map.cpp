// Tests of sensors/src/log_split.cpp and log_map.cpp: a log simulated in a known map rebuilds
// its walls and free interior (from LaserRecords and from CARMEN text, plain and gzip), the
// split into alternate blocks by time and by count, bad input and options, and the real
// Intel log of ../shared/datasets/acschaefer_ple.
#include "gridloc/sensors/log_map.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "gridloc/sensors/log_split.hpp"
#include "gridloc/sensors/scan_sim.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

/// A 10 m x 6 m room at 5 cm (walls one cell thick) with an inner wall from the south wall
/// to y = 3 m at x = 5 m, origin (-1, -2).
OccupancyMap known_map() {
  OccupancyMap map = test::walled_room(200, 120, 0.05, {-1.0, -2.0});
  for (int iy = 0; iy < 60; ++iy) map.at(100, iy) = CellState::Occupied;
  return map;
}

/// Scans of the front 180 degrees (181 beams, FLASER's layout) along a loop through the room,
/// 1 cm range noise, timestamps 2 s apart.
std::vector<LaserRecord> simulated_log(const OccupancyMap& map) {
  const std::vector<Pose2> corners = {
      {0.5, -1.0, 0}, {7.5, -1.0, kPi / 2}, {7.5, 3.0, kPi}, {0.5, 3.0, -kPi / 2}};
  std::vector<LaserRecord> log;
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const Pose2 &a = corners[c], &b = corners[(c + 1) % corners.size()];
    for (int step = 0; step < 10; ++step) {
      const double t = step / 10.0;
      const Pose2 pose{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.theta + 0.3 * t};
      const RangeScan all = simulate_scan(map, pose, 360, 8.0, 0.01, log.size() + 1);
      LaserRecord r;
      r.scan.max_range = all.max_range;
      for (int k = 90; k <= 270; ++k) {  // -90 .. +90 degrees
        r.scan.angles.push_back(all.angles[k]);
        r.scan.ranges.push_back(all.ranges[k]);
      }
      r.laser_pose = r.robot_pose = pose;
      r.timestamp = 2.0 * log.size();
      r.line = log.size() + 1;
      log.push_back(r);
    }
  }
  return log;
}

std::vector<std::size_t> every(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = k;
  return v;
}

/// The state of `truth` at the centre of cell (ix, iy) of `built` (Unknown outside).
CellState truth_at(const OccupancyMap& truth, const OccupancyMap& built, int ix, int iy) {
  const Eigen::Vector2d w = built.geometry.origin + built.geometry.cell_center(ix, iy);
  const Cell c =
      truth.geometry.cell_of(w.x() - truth.geometry.origin.x(), w.y() - truth.geometry.origin.y());
  return truth.geometry.contains(c.ix, c.iy) ? truth.at(c.ix, c.iy) : CellState::Unknown;
}

bool near_truth_wall(const OccupancyMap& truth, const OccupancyMap& built, int ix, int iy) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (truth_at(truth, built, ix + dx, iy + dy) == CellState::Occupied) return true;
    }
  }
  return false;
}

TEST(LogMap, ASimulatedLogRebuildsTheWallsAndTheFreeInterior) {
  const OccupancyMap truth = known_map();
  const std::vector<LaserRecord> log = simulated_log(truth);
  const OccupancyMap built = map_from_log(log, every(log.size()));
  EXPECT_EQ(built.geometry.resolution, 0.05);
  EXPECT_EQ(built.geometry.yaw, 0.0);
  // Every occupied cell within a cell of a true wall.
  std::size_t occupied = 0, near_wall = 0;
  for (int iy = 0; iy < built.height(); ++iy) {
    for (int ix = 0; ix < built.width(); ++ix) {
      if (built.at(ix, iy) != CellState::Occupied) continue;
      ++occupied;
      near_wall += near_truth_wall(truth, built, ix, iy);
    }
  }
  EXPECT_GT(occupied, 500u);  // the walls' length: 2 * (10 + 6) m + 3 m at 5 cm = 700 cells
  EXPECT_GE(near_wall, occupied * 99 / 100) << near_wall << " of " << occupied;
  // The interior, 2 cells or more from a wall: free, and nothing in it occupied.
  std::size_t interior = 0, free = 0;
  for (int iy = 0; iy < built.height(); ++iy) {
    for (int ix = 0; ix < built.width(); ++ix) {
      bool clear = true;
      for (int d = -2; d <= 2 && clear; ++d) {
        clear = near_truth_wall(truth, built, ix + d, iy) == false &&
                near_truth_wall(truth, built, ix, iy + d) == false;
      }
      const Eigen::Vector2d w = built.geometry.origin + built.geometry.cell_center(ix, iy);
      if (!clear || w.x() < -0.9 || w.x() > 8.9 || w.y() < -1.9 || w.y() > 3.9) continue;
      ++interior;
      free += built.at(ix, iy) == CellState::Free;
    }
  }
  EXPECT_GT(interior, 15000u);
  EXPECT_GE(free, interior * 97 / 100) << free << " of " << interior;
  // Nothing drawn beyond the room: the map spans the walls plus the 1 m margin.
  EXPECT_NEAR(built.geometry.origin.x(), -1.0 - 1.0, 0.06);
  EXPECT_NEAR(built.geometry.width * 0.05, 10.0 + 2.0, 0.15);
  const CellCounts counts = count_cells(built);
  EXPECT_EQ(counts.occupied, occupied);
  EXPECT_EQ(counts.occupied + counts.free + counts.unknown, built.cells.size());
}

TEST(LogMap, FarReturnsAndMissingReturnsLeaveNoHit) {
  LaserRecord r;
  r.scan = {{0.0, kPi / 2, kPi}, {2.0, 30.0, 80.0}, 80.0};  // a wall at 2 m, one at 30 m, none
  LogMapOptions options;
  options.resolution = 0.5;
  options.margin_m = 0.0;
  OccupancyMap map = map_from_log({r}, {0}, options);
  // Only the 2 m beam is drawn: the map spans x in [0, 2], its end cell occupied.
  EXPECT_EQ(count_cells(map).occupied, 1u);
  EXPECT_LE(map.geometry.height, 2);
  EXPECT_EQ(map.at(map.width() - 1, 0), CellState::Occupied);
  EXPECT_EQ(map.at(0, 0), CellState::Free);
  // Drawn free up to 5 m when asked: north and west, without an end.
  options.no_return_free_m = 5.0;
  map = map_from_log({r}, {0}, options);
  EXPECT_EQ(count_cells(map).occupied, 1u);
  EXPECT_NEAR(map.geometry.height * 0.5, 5.5, 1e-9);
  EXPECT_NEAR(map.geometry.origin.x(), -5.0, 1e-9);
  EXPECT_EQ(map.at(0, 0), CellState::Free);  // x = -5: the west beam's end, passed
}

TEST(LogMap, AHitBeatsAFewPassesButNotMany) {
  // Beam 0 ends in the cell x in [2, 2.5); the other beams cross it on their way to 4 m.
  auto map_with = [](int crossing) {
    LaserRecord r;
    r.scan.max_range = 80.0;
    r.scan.angles.assign(1 + crossing, 0.0);
    r.scan.ranges.assign(1 + crossing, 4.2);
    r.scan.ranges[0] = 2.2;
    LogMapOptions options;
    options.resolution = 0.5;
    options.margin_m = 0.0;
    const OccupancyMap map = map_from_log({r}, {0}, options);
    return map.at(4, 0);
  };
  EXPECT_EQ(map_with(3), CellState::Occupied);  // 1 / 4 = occupied_ratio
  EXPECT_EQ(map_with(4), CellState::Free);
}

/// The simulated log as CARMEN FLASER lines (181 readings from -90 degrees).
std::string flaser_text(const std::vector<LaserRecord>& log) {
  std::ostringstream out;
  out.precision(9);
  for (const LaserRecord& r : log) {
    out << "FLASER " << r.scan.ranges.size();
    for (const double range : r.scan.ranges) out << " " << range;
    for (int twice = 0; twice < 2; ++twice) {
      out << " " << r.laser_pose.x << " " << r.laser_pose.y << " " << r.laser_pose.theta;
    }
    out << " " << r.timestamp << " sim " << r.timestamp << "\n";
  }
  return out.str();
}

TEST(LogMap, TheSameMapFromRecordsFromCarmenTextAndFromGzip) {
  const std::vector<LaserRecord> log = simulated_log(known_map());
  test::TempDir dir;
  const std::string text = flaser_text(log);
  const std::string plain = dir.write("sim.log", text);
  const std::string gz = dir.file("sim.log.gz");
  gzFile file = gzopen(gz.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  const CarmenLog from_plain = load_carmen_log(plain), from_gz = load_carmen_log(gz);
  ASSERT_EQ(from_plain.lasers.size(), log.size());
  const OccupancyMap a = map_from_log(from_plain, every(log.size()));
  const OccupancyMap b = map_from_log(from_gz, every(log.size()));
  const OccupancyMap c = map_from_log(log, every(log.size()));
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.geometry.origin, b.geometry.origin);
  // The text rounds to 9 digits: the same map, cell for cell, but a hair of a margin.
  EXPECT_EQ(a.geometry.width, c.geometry.width);
  EXPECT_EQ(a.geometry.height, c.geometry.height);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.cells.size(); ++k) differ += a.cells[k] != c.cells[k];
  EXPECT_LE(differ, a.cells.size() / 1000);
}

std::vector<LaserRecord> records_at(const std::vector<double>& times) {
  std::vector<LaserRecord> log(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    log[k].timestamp = times[k];
    log[k].timestamp_resolution = 0.01;
    log[k].line = k + 1;
  }
  return log;
}

using Indices = std::vector<std::size_t>;

TEST(LogSplit, AlternateBlocksByTime) {
  // Blocks of 30 s from t = 100: [100, 130) [130, 160) [160, 190) [190, 220).
  const auto log = records_at({100, 110, 129.9, 130, 150, 161, 175, 200, 219});
  const LogSplit split = split_log(log);
  EXPECT_EQ(split.rule, SplitRule::TimeBlocks);
  EXPECT_EQ(split.map, (Indices{0, 1, 2, 5, 6}));
  EXPECT_EQ(split.held_out, (Indices{3, 4, 7, 8}));
  EXPECT_EQ(split.blocks, 4u);
  EXPECT_EQ(split.timestamps_unusable, "");
  EXPECT_EQ(to_string(split.rule), "time blocks");
  // An empty block (a pause in the log) keeps its parity: 100 and 165 are blocks 0 and 2.
  EXPECT_EQ(split_log(records_at({100, 165})).map, (Indices{0, 1}));
  // A scan a little early stays in its predecessor's block.
  const LogSplit early = split_log(records_at({100, 131, 130.5, 140}));
  EXPECT_EQ(early.map, (Indices{0}));
  EXPECT_EQ(early.held_out, (Indices{1, 2, 3}));
  LogSplitOptions options;
  options.block_s = 10;
  EXPECT_EQ(split_log(log, options).map, (Indices{0, 2, 5, 7}));  // blocks 0, 2, 6, 10
}

TEST(LogSplit, AlternateBlocksByCountWhenTheTimestampsAreUnusable) {
  LogSplitOptions options;
  options.block_scans = 2;
  const auto expect_count_split = [&](const std::vector<LaserRecord>& log, const std::string& why) {
    const LogSplit split = split_log(log, options);
    EXPECT_EQ(split.rule, SplitRule::ScanBlocks);
    EXPECT_EQ(split.map, (Indices{0, 1, 4}));
    EXPECT_EQ(split.held_out, (Indices{2, 3}));
    EXPECT_EQ(split.blocks, 3u);
    EXPECT_NE(split.timestamps_unusable.find(why), std::string::npos) << split.timestamps_unusable;
  };
  expect_count_split(records_at({0, 0, 0, 0, 0}), "span 0 s");  // freiburg-campus, orebro
  expect_count_split(records_at({0, 10, 20, 25, 29}), "span 29 s");
  expect_count_split(records_at({0, 50, 40, 60, 70}), "line 3's timestamp 40 steps back");
  expect_count_split(records_at({0, 50, NAN, 60, 70}), "line 3's timestamp is not finite");
  auto coarse = records_at({1.13486e9, 1.13486e9, 1.13487e9, 1.13487e9, 1.13487e9});  // csail
  for (LaserRecord& r : coarse) r.timestamp_resolution = 1e4;
  expect_count_split(coarse, "printed to 10000 s only");
  EXPECT_EQ(timestamp_problem(records_at({0, 31})), "");
}

TEST(LogSplit, AllScans) {
  const LogSplit split = all_scans(records_at({0, 0, 0}));
  EXPECT_EQ(split.rule, SplitRule::All);
  EXPECT_EQ(split.map, (Indices{0, 1, 2}));
  EXPECT_TRUE(split.held_out.empty());
  EXPECT_EQ(to_string(SplitRule::All), "all");
  EXPECT_EQ(to_string(SplitRule::ScanBlocks), "scan blocks");
}

TEST(LogSplit, BadInputAndOptions) {
  test::expect_error([] { split_log({}); }, {"no laser scan"});
  test::expect_error([] { all_scans({}); }, {"no laser scan"});
  const auto log = records_at({0, 40});
  test::expect_error([&] { split_log(log, {0.0, 10, 1.0}); }, {"block_s", "> 0"});
  test::expect_error([&] { split_log(log, {NAN, 10, 1.0}); }, {"block_s"});
  test::expect_error([&] { split_log(log, {30.0, 0, 1.0}); }, {"block_scans", ">= 1"});
  test::expect_error([&] { split_log(log, {30.0, 10, -1.0}); }, {"max_backstep_s"});
}

TEST(LogMap, BadInputAndOptions) {
  const std::vector<LaserRecord> log = simulated_log(known_map());
  test::expect_error([&] { map_from_log(log, {}); }, {"no scan"});
  test::expect_error([&] { map_from_log(log, {0, 40}); }, {"scan index 40", "40 scans"});
  std::vector<LaserRecord> bad = log;
  bad[3].scan.ranges[5] = -1.0;
  test::expect_error([&] { map_from_log(bad, {2, 3}); }, {"line 4", "range"});
  bad = log;
  bad[2].laser_pose.y = NAN;
  test::expect_error([&] { map_from_log(bad, {2, 3}); }, {"line 3", "laser pose", "not finite"});
  bad = log;
  bad[2].scan.angles.pop_back();
  test::expect_error([&] { map_from_log(bad, {2}); }, {"line 3", "angles"});
  // A scan without any return is no error: it draws nothing.
  bad = log;
  bad[2].scan.ranges.assign(bad[2].scan.ranges.size(), 80.0);
  EXPECT_EQ(map_from_log(bad, {1, 2}).cells, map_from_log(log, {1}).cells);
  const auto expect_option_error = [&](auto change, const std::string& field) {
    LogMapOptions options;
    change(options);
    test::expect_error([&] { map_from_log(log, {0}, options); }, {field});
    test::expect_error([&] { validate(options); }, {field});
  };
  expect_option_error([](LogMapOptions& o) { o.resolution = 0; }, "resolution");
  expect_option_error([](LogMapOptions& o) { o.resolution = NAN; }, "resolution");
  expect_option_error([](LogMapOptions& o) { o.max_range_m = -1; }, "max_range_m");
  expect_option_error([](LogMapOptions& o) { o.no_return_free_m = -1; }, "no_return_free_m");
  expect_option_error([](LogMapOptions& o) { o.margin_m = INFINITY; }, "margin_m");
  expect_option_error([](LogMapOptions& o) { o.min_hits = 0; }, "min_hits");
  expect_option_error([](LogMapOptions& o) { o.min_passes = 70000; }, "min_passes");
  expect_option_error([](LogMapOptions& o) { o.occupied_ratio = 0; }, "occupied_ratio");
  expect_option_error([](LogMapOptions& o) { o.occupied_ratio = 1.5; }, "occupied_ratio");
  expect_option_error([](LogMapOptions& o) { o.limits.max_cells = 0; }, "max_cells");
  // The cap is checked before anything is allocated, and the message gives the size.
  LogMapOptions small;
  small.limits.max_cells = 10000;
  test::expect_error(
      [&] { map_from_log(log, every(log.size()), small); },
      {"map from log", "cells exceeds the limit of 10000 cells", "m x", "--max-cells"});
  LogMapOptions fine;
  fine.resolution = 1e-4;  // 12 m at 0.1 mm: 1.4e10 cells
  test::expect_error([&] { map_from_log(log, every(log.size()), fine); }, {"--max-cells"});
  LogMapOptions tight;
  tight.limits.max_memory_mb = 0.001;  // the cells fit, the memory does not
  test::expect_error([&] { map_from_log(log, every(log.size()), tight); }, {"--max-memory-mb"});
  LaserRecord far;
  far.scan = {{0.0}, {15.0}, 80.0};
  far.laser_pose = {1e9, 0, 0};  // a wild pose beside a sane one
  std::vector<LaserRecord> wild = log;
  wild.push_back(far);
  test::expect_error([&] { map_from_log(wild, {0, wild.size() - 1}); }, {"--max-cells"});
}

// A real building: the Intel lab's corrected log, its map part drawn.
TEST(LogMap, TheIntelLogsMapPart) {
  const std::string path =
      std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/acschaefer_ple/intel-corrected.log.gz";
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << "../shared is absent (" << path << "): real-log test skipped";
  }
  const CarmenLog log = load_carmen_log(path);
  ASSERT_EQ(log.lasers.size(), 910u);
  const LogSplit split = split_log(log.lasers);
  EXPECT_EQ(split.rule, SplitRule::TimeBlocks);  // its few early scans are tolerated
  EXPECT_EQ(split.map.size() + split.held_out.size(), 910u);
  EXPECT_GT(split.map.size(), 400u);
  EXPECT_GT(split.held_out.size(), 400u);
  const OccupancyMap map = map_from_log(log, split.map);
  // The lab is about 30 m x 30 m (the dataset's render); beams reach out of its windows.
  const double width_m = map.width() * map.geometry.resolution;
  const double height_m = map.height() * map.geometry.resolution;
  EXPECT_GT(width_m, 30.0);
  EXPECT_LT(width_m, 50.0);
  EXPECT_GT(height_m, 30.0);
  EXPECT_LT(height_m, 50.0);
  const CellCounts cells = count_cells(map);
  EXPECT_GT(cells.occupied, 8000u);  // 30 m x 4 sides plus rooms: > 400 m of wall at 5 cm
  EXPECT_GT(cells.free, 150000u);    // > 375 m^2 of floor
  EXPECT_GT(cells.free, 10 * cells.occupied);
}

}  // namespace
}  // namespace gridloc
