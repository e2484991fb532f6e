// Tests of sensors/src/carmen_log.cpp: CARMEN logs (FLASER, ROBOTLASER1, ODOM) from a
// hand-written excerpt, plain and gzip-compressed, real logs from ../shared/datasets, and
// malformed input.
#include "gridloc/sensors/carmen_log.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "test_support.hpp"

namespace gridloc {
namespace {

constexpr double kPi = std::numbers::pi;

CarmenLog parse(const std::string& text) {
  std::istringstream in(text);
  return parse_carmen_log(in, "excerpt.log");
}

TEST(CarmenLog, ReadsLasersAndOdometryAndSkipsTheRest) {
  const CarmenLog log = parse(
      "# a comment\n"
      "PARAM robot_front_laser_max 81.9 nohost 0\n"
      "ODOM 1.5 -2 0.25 0.3 -0.1 0 12.5 pippo 12.5\n"
      "FLASER 3 1.0 2.5 81.91 0.5 0.25 -1.5 0.4 0.2 -1.4 13.25 pippo 13.25\n"
      "NEFF 15\n"
      "\n"
      "FLASER 4 1 2 3 4 0 0 0 0 0 0 14 pippo 14\n"
      "ROBOTLASER1 0 -1.5 3.0 0.5 8.0 0.01 0 5 1 2 3 8.5 4 0 0.1 0.2 0.3 1 2 3 0 0 0 0 0 15.5 "
      "pippo 15.5\n");
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.odometry[0].pose.x, 1.5);
  EXPECT_EQ(log.odometry[0].pose.theta, 0.25);
  EXPECT_EQ(log.odometry[0].tv, 0.3);
  EXPECT_EQ(log.odometry[0].timestamp, 12.5);
  EXPECT_EQ(log.odometry[0].line, 3u);
  ASSERT_EQ(log.lasers.size(), 3u);
  // Odd count: both ends of the 180 degree field.
  const LaserRecord& a = log.lasers[0];
  EXPECT_EQ(a.scan.ranges, (std::vector<double>{1.0, 2.5, 81.91}));
  ASSERT_EQ(a.scan.angles.size(), 3u);
  EXPECT_NEAR(a.scan.angles[0], -kPi / 2, 1e-12);
  EXPECT_NEAR(a.scan.angles[1], 0.0, 1e-12);
  EXPECT_NEAR(a.scan.angles[2], kPi / 2, 1e-12);
  EXPECT_EQ(a.scan.max_range, 80.0);  // 81.91 is no return
  EXPECT_EQ(a.laser_pose.x, 0.5);
  EXPECT_EQ(a.laser_pose.theta, -1.5);
  EXPECT_EQ(a.robot_pose.theta, -1.4);
  EXPECT_EQ(a.timestamp, 13.25);
  EXPECT_EQ(a.line, 4u);
  // Even count: a step short of +90 degrees.
  const LaserRecord& b = log.lasers[1];
  EXPECT_NEAR(b.scan.angles[1] - b.scan.angles[0], kPi / 4, 1e-12);
  EXPECT_NEAR(b.scan.angles[3], kPi / 4, 1e-12);
  // ROBOTLASER1 carries its own geometry and max range; remissions are skipped.
  const LaserRecord& c = log.lasers[2];
  EXPECT_EQ(c.scan.ranges, (std::vector<double>{1, 2, 3, 8.5, 4}));
  EXPECT_NEAR(c.scan.angles[0], -1.5, 1e-12);
  EXPECT_NEAR(c.scan.angles[4], 0.5, 1e-12);
  EXPECT_EQ(c.scan.max_range, 8.0);
  EXPECT_EQ(c.laser_pose.x, 0.1);
  EXPECT_EQ(c.robot_pose.x, 1.0);
  EXPECT_EQ(c.timestamp, 15.5);
}

TEST(CarmenLog, MalformedLinesNameTheLineAndField) {
  test::expect_error([] { parse("ODOM 1 2\n"); }, {"excerpt.log:1", "ODOM", "ends before"});
  test::expect_error([] { parse("\nODOM 1 2 x 0 0 0 1 h 1\n"); },
                     {"excerpt.log:2", "pose theta", "not a number", "'x'"});
  test::expect_error([] { parse("FLASER 3 1 2\n"); }, {"FLASER", "range 3 of 3", "ends before"});
  test::expect_error([] { parse("FLASER 2.5 1 2 0 0 0 0 0 0 1 h 1\n"); },
                     {"reading count", "whole number"});
  test::expect_error([] { parse("FLASER 2 1 -2 0 0 0 0 0 0 1 h 1\n"); },
                     {"range 2", "must be >= 0"});
  test::expect_error([] { parse("FLASER 1 1 0 0 0 0 0 0 1 h 1\n"); }, {"at least 2 readings"});
  test::expect_error([] { parse("FLASER 2 1 2 0 0 inf 0 0 0 1 h 1\n"); },
                     {"laser pose", "not finite"});
}

TEST(CarmenLog, TimestampResolutionIsTheUnitOfTheLastDigit) {
  const CarmenLog log = parse(
      "FLASER 2 1 2 0 0 0 0 0 0 1777.35 h 1\n"
      "FLASER 2 1 2 0 0 0 0 0 0 14 h 1\n"
      "FLASER 2 1 2 0 0 0 0 0 0 1.13486e+09 h 1\n"  // csail's absolute times: 10^4 s
      "FLASER 2 1 2 0 0 0 0 0 0 25E-1 h 1\n");
  ASSERT_EQ(log.lasers.size(), 4u);
  EXPECT_NEAR(log.lasers[0].timestamp_resolution, 0.01, 1e-15);
  EXPECT_EQ(log.lasers[1].timestamp_resolution, 1.0);
  EXPECT_NEAR(log.lasers[2].timestamp_resolution, 1e4, 1e-9);
  EXPECT_NEAR(log.lasers[3].timestamp_resolution, 0.1, 1e-15);
}

TEST(CarmenLog, InvalidBeamsReadAsNoReturn) {
  const CarmenLog log = parse("FLASER 3 1 nan inf 0 0 0 0 0 0 1 h 1\n");
  ASSERT_EQ(log.lasers.size(), 1u);
  EXPECT_EQ(log.lasers[0].scan.ranges, (std::vector<double>{1.0, 80.0, 80.0}));
  EXPECT_EQ(log.lasers[0].invalid_ranges, 2);
}

TEST(CarmenLog, FileErrors) {
  test::TempDir dir;
  const std::string missing = dir.file("none.log");
  test::expect_error([&] { load_carmen_log(missing); }, {missing, "not found"});
  const std::string ok = dir.write("ok.log", "ODOM 0 0 0 0 0 0 1 h 1\n");
  EXPECT_EQ(load_carmen_log(ok).odometry.size(), 1u);
  CarmenOptions options;
  options.max_range = -1.0;
  test::expect_error([&] { load_carmen_log(ok, options); }, {"max_range"});
  options = {};
  options.max_decompressed_bytes = 0;
  test::expect_error([&] { load_carmen_log(ok, options); }, {"max_decompressed_bytes"});
}

const char* const kExcerpt =
    "PARAM robot_front_laser_max 81.9 nohost 0\n"
    "ODOM 1.5 -2 0.25 0.3 -0.1 0 12.5 pippo 12.5\n"
    "FLASER 3 1.0 2.5 81.91 0.5 0.25 -1.5 0.4 0.2 -1.4 13.25 pippo 13.25\n"
    "FLASER 4 1 2 3 4 0 0 0 0 0 0 14 pippo 14\n";

/// `text` gzip-compressed by zlib, as gzip(1) writes it.
std::string gzip(const std::string& text, const test::TempDir& dir) {
  const std::string path = dir.file("compressed.gz");
  gzFile file = gzopen(path.c_str(), "wb");
  EXPECT_NE(file, nullptr);
  // A long text, so the compressed data span several blocks and can be cut in the middle.
  EXPECT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  gzclose(file);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void expect_same(const CarmenLog& a, const CarmenLog& b) {
  ASSERT_EQ(a.lasers.size(), b.lasers.size());
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t k = 0; k < a.lasers.size(); ++k) {
    EXPECT_EQ(a.lasers[k].scan.ranges, b.lasers[k].scan.ranges);
    EXPECT_EQ(a.lasers[k].scan.angles, b.lasers[k].scan.angles);
    EXPECT_EQ(a.lasers[k].laser_pose.x, b.lasers[k].laser_pose.x);
    EXPECT_EQ(a.lasers[k].timestamp, b.lasers[k].timestamp);
    EXPECT_EQ(a.lasers[k].line, b.lasers[k].line);
  }
  for (std::size_t k = 0; k < a.odometry.size(); ++k) {
    EXPECT_EQ(a.odometry[k].pose.y, b.odometry[k].pose.y);
  }
}

TEST(CarmenLog, ReadsGzipAsItReadsPlainText) {
  test::TempDir dir;
  std::string text;
  for (int k = 0; k < 2000; ++k) text += kExcerpt;  // ~300 kB: several zlib buffers
  const std::string plain = dir.write("plain.log", text);
  const std::string gz = dir.write("log.gz", gzip(text, dir));
  const CarmenLog a = load_carmen_log(plain), b = load_carmen_log(gz);
  EXPECT_EQ(a.lasers.size(), 4000u);
  expect_same(a, b);
  // The name does not matter: a gzip named .log is read, a plain file named .gz too.
  expect_same(a, load_carmen_log(dir.write("gzip-named.log", gzip(text, dir))));
  expect_same(a, load_carmen_log(dir.write("plain-named.gz", text)));
}

TEST(CarmenLog, CorruptOrTruncatedGzipNamesTheFile) {
  test::TempDir dir;
  std::string text;
  for (int k = 0; k < 2000; ++k) text += kExcerpt;
  const std::string compressed = gzip(text, dir);
  const std::string cut = dir.write("cut.log.gz", compressed.substr(0, compressed.size() / 2));
  test::expect_error([&] { load_carmen_log(cut); }, {cut, "truncated gzip"});
  std::string damaged = compressed;
  for (std::size_t k = 20; k < 60; ++k) damaged[k] = static_cast<char>(damaged[k] ^ 0x5a);
  const std::string bad = dir.write("bad.log.gz", damaged);
  test::expect_error([&] { load_carmen_log(bad); }, {bad, "corrupt gzip"});
  const std::string header = dir.write("header.gz", std::string("\x1f\x8b\x08\x00", 4));
  test::expect_error([&] { load_carmen_log(header); }, {header, "gzip"});
}

TEST(CarmenLog, TheTextReadIsBounded) {
  test::TempDir dir;
  std::string text;
  for (int k = 0; k < 2000; ++k) text += kExcerpt;
  const std::string gz = dir.write("log.gz", gzip(text, dir));
  CarmenOptions options;
  options.max_decompressed_bytes = 100000;  // a third of the text
  test::expect_error([&] { load_carmen_log(gz, options); },
                     {gz, "more than 100000 bytes", "max_decompressed_bytes"});
  const std::string plain = dir.write("plain.log", text);
  test::expect_error([&] { load_carmen_log(plain, options); }, {plain, "more than 100000"});
  options.max_decompressed_bytes = text.size();
  EXPECT_EQ(load_carmen_log(gz, options).lasers.size(), 4000u);
}

// A real log nobody here produced: the GMapping-corrected Intel lab log.
TEST(CarmenLog, ReadsTheIntelLog) {
  const std::string path = std::string(GRIDLOC_TEST_SHARED_DIR) +
                           "/datasets/xiaofeng419_SLAM-2D-LIDAR-SCAN/intel.gfs.log";
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << "../shared is absent (" << path << "): real-log test skipped";
  }
  const CarmenLog log = load_carmen_log(path);
  EXPECT_EQ(log.lasers.size(), 910u);  // its FLASER lines
  EXPECT_EQ(log.odometry.size(), 14541u);
  for (const LaserRecord& r : log.lasers) {
    ASSERT_EQ(r.scan.ranges.size(), 180u) << "line " << r.line;
    EXPECT_NO_THROW(validate(r.scan)) << "line " << r.line;
  }
  // The first scan as the file gives it (its last fields: pose x y theta twice, timestamps).
  const LaserRecord& first = log.lasers.front();
  EXPECT_NEAR(first.timestamp, 32.9068, 1e-9);
  EXPECT_NEAR(first.laser_pose.x, 0.600266, 1e-9);
  EXPECT_NEAR(first.laser_pose.y, -0.0320327, 1e-9);
  EXPECT_NEAR(first.laser_pose.theta, -0.354665, 1e-9);
  // (The log's timestamps are not all in order: a few scans come 0.05-0.9 s early.)
}

// Another real log, whose lines end in "0 0 <name>" instead of host and logger timestamp.
TEST(CarmenLog, ReadsTheLaserazosLog) {
  const std::string path =
      std::string(GRIDLOC_TEST_SHARED_DIR) + "/datasets/AndreaCensi_csm/laserazosSM3.log";
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << "../shared is absent (" << path << "): real-log test skipped";
  }
  const CarmenLog log = load_carmen_log(path);
  ASSERT_EQ(log.lasers.size(), 778u);
  for (const LaserRecord& r : log.lasers) ASSERT_EQ(r.scan.ranges.size(), 361u) << r.line;
  const RangeScan& s = log.lasers.front().scan;
  EXPECT_NEAR(s.angles[1] - s.angles[0], std::numbers::pi / 360, 1e-12);  // 0.5 degree
  EXPECT_EQ(s.ranges.front(), 3.727);
  int invalid = 0;  // the log marks invalid beams "nan"
  for (const LaserRecord& r : log.lasers) invalid += r.invalid_ranges;
  EXPECT_GT(invalid, 0);
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14: the file is checked where it enters (plain or gzip), declared beam counts against
// max_beams before any range is read, and the records against max_memory_mb as they grow.
TEST(CarmenLog, InputLimits) {
  test::TempDir dir;
  test::expect_error([&] { load_carmen_log(dir.path().string()); },
                     {dir.path().string(), "is a directory", "CARMEN log"});
  const std::string plain = dir.write("log", kExcerpt);
  const std::string gz = dir.write("log.gz", gzip(kExcerpt, dir));
  CarmenOptions options;
  options.limits.max_file_mb = 1e-6;
  for (const std::string& p : {plain, gz}) {
    test::expect_error([&] { load_carmen_log(p, options); }, {p, "--max-file-mb"});
  }
  options = {};
  options.limits.max_beams = 3;  // the excerpt's second scan has 4
  test::expect_error([&] { load_carmen_log(gz, options); },
                     {gz, ":4: FLASER", "reading count", "4 beams", "--max-beams"});
  // A declared count far beyond the line is refused before anything is reserved for it.
  std::istringstream huge("FLASER 1000000000 1 2\n");
  test::expect_error([&] { parse_carmen_log(huge, "huge.log"); },
                     {"huge.log:1", "1e+09 beams", "--max-beams"});
  std::istringstream remissions(
      "ROBOTLASER1 0 -1.5 3.1 0.01 80 0.1 0 2 1 1 200000 0 0 0 0 0 0 0 0 0 0 0 0 5 h 5\n");
  test::expect_error([&] { parse_carmen_log(remissions, "r.log"); },
                     {"remission count", "--max-beams"});
  options = {};
  options.limits.max_memory_mb = 1e-6;
  test::expect_error([&] { load_carmen_log(plain, options); }, {plain, "--max-memory-mb"});
}

}  // namespace
}  // namespace gridloc
