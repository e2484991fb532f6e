// Tests of sensors/src/readings_io.cpp: readings JSON files.
#include "gridloc/sensors/readings_io.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;
using test::TempDir;

TEST(ReadingsIo, LoadsRangesAndIgnoresOtherKeys) {
  TempDir dir;
  const std::string p =
      dir.write("r.json", R"({"pose": {"x": 1, "y": 2, "theta": 0}, "ranges_m": [1.5, 6, 0.25]})");
  EXPECT_EQ(load_readings(p), (std::vector<double>{1.5, 6.0, 0.25}));
}

TEST(ReadingsIo, NullIsReadAsNaN) {
  TempDir dir;
  const std::string p = dir.write("r.json", R"({"ranges_m": [1.0, null]})");
  const auto r = load_readings(p);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0], 1.0);
  EXPECT_TRUE(std::isnan(r[1]));
}

TEST(ReadingsIo, FiringsAreReadOrRangesAreOneFiring) {
  TempDir dir;
  const std::string several =
      dir.write("f.json", R"({"ranges_m": [9], "firings_m": [[1.5, 6], [1.4, null], [1.5, 2]]})");
  const auto f = load_firings(several);
  ASSERT_EQ(f.size(), 3u);  // firings_m wins over ranges_m
  EXPECT_EQ(f[0], (std::vector<double>{1.5, 6.0}));
  EXPECT_TRUE(std::isnan(f[1][1]));
  EXPECT_EQ(f[2], (std::vector<double>{1.5, 2.0}));
  const std::string one = dir.write("r.json", R"({"ranges_m": [1.5, 6]})");
  EXPECT_EQ(load_firings(one), (std::vector<std::vector<double>>{{1.5, 6.0}}));
  const std::string flat = dir.write("bad.json", R"({"firings_m": [1.5, 6]})");
  expect_error([&] { load_firings(flat); }, {flat, "firings_m", "arrays"});
  const std::string empty = dir.write("empty.json", R"({"firings_m": []})");
  expect_error([&] { load_firings(empty); }, {empty, "non-empty"});
  const std::string text = dir.write("text.json", R"({"firings_m": [[1.0, "x"]]})");
  expect_error([&] { load_firings(text); }, {text, "numbers"});
  const std::string neither = dir.write("none.json", R"({"pose": {}})");
  expect_error([&] { load_firings(neither); }, {neither, "ranges_m", "firings_m"});
}

TEST(ReadingsIo, Errors) {
  TempDir dir;
  const std::string missing = dir.file("none.json");
  expect_error([&] { load_readings(missing); }, {missing, "not found"});
  const std::string malformed = dir.write("a.json", R"({"ranges_m": [1.0, )");
  expect_error([&] { load_readings(malformed); }, {malformed, "malformed JSON"});
  const std::string no_key = dir.write("b.json", R"({"ranges": [1.0]})");
  expect_error([&] { load_readings(no_key); }, {no_key, "ranges_m"});
  const std::string not_array = dir.write("c.json", R"({"ranges_m": 2.0})");
  expect_error([&] { load_readings(not_array); }, {not_array, "ranges_m"});
  const std::string text = dir.write("d.json", R"({"ranges_m": [1.0, "far"]})");
  expect_error([&] { load_readings(text); }, {text, "ranges_m", "far"});
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14: the file is checked where it enters, and the values are counted while parsing.
TEST(ReadingsIoLimits, DirectoriesLargeFilesAndTooManyValuesAreNamed) {
  TempDir dir;
  expect_error([&] { load_readings(dir.path().string()); },
               {dir.path().string(), "is a directory", "readings file"});
  expect_error([&] { load_firings(dir.path().string()); }, {"is a directory"});
  const std::string p = dir.write("r.json", R"({"ranges_m": [1, 2, 3]})");
  ResourceLimits tiny_file;
  tiny_file.max_file_mb = 1e-6;
  expect_error([&] { load_readings(p, tiny_file); }, {p, "--max-file-mb"});
  ResourceLimits three;
  three.max_beams = 3;
  EXPECT_EQ(load_readings(p, three).size(), 3u);
  const std::string four = dir.write("four.json", R"({"ranges_m": [1, 2, 3, 4]})");
  expect_error([&] { load_readings(four, three); }, {four, "4 values", "--max-beams"});
  const std::string firings = dir.write("f.json", R"({"firings_m": [[1, 2], [3, 4]]})");
  expect_error([&] { load_firings(firings, three); }, {firings, "--max-beams"});
}

}  // namespace
}  // namespace gridloc
