// Tests of sensors/src/sonar_ring.cpp: ring YAML loading, validation, readings checks.
#include "gridloc/sensors/sonar_ring.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "gridloc/grids/geometry.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;
using test::TempDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A ring file with one sonar whose fields are `sonar` (a YAML flow mapping body).
std::string ring_yaml(const std::string& sonar, const std::string& top = "") {
  return "name: test\n" + top + "sonars:\n  - {" + sonar + "}\n";
}

TEST(SonarRing, LoadsTheBundledRing) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EXPECT_EQ(ring.name, "vahm-wheelchair-14");
  ASSERT_EQ(ring.sonars.size(), 14u);
  for (const auto& s : ring.sonars) {
    EXPECT_NEAR(s.cone, deg2rad(12.0), 1e-12);
    EXPECT_EQ(s.min_range, 0.15);
    EXPECT_EQ(s.max_range, 6.0);
  }
  EXPECT_NEAR(ring.sonars[0].bearing, deg2rad(-28.61), 1e-12);
  EXPECT_NEAR(ring.sonars[0].radius, 0.6265, 1e-12);
  EXPECT_NEAR(ring.sonars[0].heading, deg2rad(-30.0), 1e-12);
  EXPECT_NEAR(ring.sonars[5].bearing, deg2rad(90.0), 1e-12);
  EXPECT_NEAR(ring.sonars[5].radius, 0.35, 1e-12);
  EXPECT_NEAR(ring.sonars[13].heading, deg2rad(-75.0), 1e-12);
  ASSERT_EQ(ring.footprint.polygon.size(), 4u);
  EXPECT_EQ(ring.footprint.polygon[0], Eigen::Vector2d(0.55, 0.35));
  EXPECT_NEAR(ring.reach(), 0.6265 + 6.0, 1e-12);
}

TEST(SonarRing, PerSonarValuesOverrideDefaults) {
  TempDir dir;
  const std::string p =
      dir.write("r.yaml",
                "defaults: {cone_deg: 20, min_range_m: 0.2, max_range_m: 4}\n"
                "sonars:\n"
                "  - {bearing_deg: 0, radius_m: 0.3, heading_deg: 0}\n"
                "  - {bearing_deg: 90, radius_m: 0.3, heading_deg: 90, cone_deg: 8, "
                "max_range_m: 3}\n");
  const SonarRing ring = load_sonar_ring(p);
  ASSERT_EQ(ring.sonars.size(), 2u);
  EXPECT_EQ(ring.name, p);  // no name: the file's path
  EXPECT_NEAR(ring.sonars[0].cone, deg2rad(20.0), 1e-12);
  EXPECT_EQ(ring.sonars[0].min_range, 0.2);
  EXPECT_EQ(ring.sonars[0].max_range, 4.0);
  EXPECT_NEAR(ring.sonars[1].cone, deg2rad(8.0), 1e-12);
  EXPECT_EQ(ring.sonars[1].min_range, 0.2);
  EXPECT_EQ(ring.sonars[1].max_range, 3.0);
  EXPECT_TRUE(ring.footprint.polygon.empty());
}

TEST(SonarRing, FootprintContains) {
  const SonarRing ring = load_sonar_ring(test::ring_path());
  EXPECT_TRUE(footprint_contains(ring.footprint, {0.0, 0.0}));
  EXPECT_TRUE(footprint_contains(ring.footprint, {0.5, -0.3}));
  EXPECT_TRUE(footprint_contains(ring.footprint, {-0.54, 0.34}));
  EXPECT_FALSE(footprint_contains(ring.footprint, {0.6, 0.0}));
  EXPECT_FALSE(footprint_contains(ring.footprint, {0.0, -0.4}));
  EXPECT_FALSE(footprint_contains(ring.footprint, {-3.0, 2.0}));
}

// ---- bad ring files --------------------------------------------------------------------

TEST(SonarRingErrors, MissingFile) {
  TempDir dir;
  const std::string p = dir.file("none.yaml");
  expect_error([&] { load_sonar_ring(p); }, {p, "not found"});
}

TEST(SonarRingErrors, MalformedYaml) {
  TempDir dir;
  const std::string p = dir.write("r.yaml", "sonars: [ {bearing_deg: 0\n");
  expect_error([&] { load_sonar_ring(p); }, {p, "malformed YAML"});
}

TEST(SonarRingErrors, UnknownKeys) {
  TempDir dir;
  const std::string in_sonar =
      dir.write("a.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0, colour: red"));
  expect_error([&] { load_sonar_ring(in_sonar); }, {in_sonar, "sonars[0]", "colour"});
  const std::string top = dir.write(
      "b.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0", "frame: base\n"));
  expect_error([&] { load_sonar_ring(top); }, {top, "frame"});
  const std::string defaults =
      dir.write("c.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0",
                                    "defaults: {cone_deg: 12, max_range: 6}\n"));
  expect_error([&] { load_sonar_ring(defaults); }, {defaults, "defaults", "max_range"});
}

TEST(SonarRingErrors, MissingRequiredField) {
  TempDir dir;
  const std::string p = dir.write("r.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3"));
  expect_error([&] { load_sonar_ring(p); }, {p, "sonars[0]", "heading_deg"});
  const std::string q = dir.write("q.yaml", ring_yaml("heading_deg: 0, radius_m: 0.3"));
  expect_error([&] { load_sonar_ring(q); }, {q, "bearing_deg"});
}

TEST(SonarRingErrors, NegativeRadius) {
  TempDir dir;
  const std::string p =
      dir.write("r.yaml", ring_yaml("bearing_deg: 0, radius_m: -0.1, heading_deg: 0"));
  expect_error([&] { load_sonar_ring(p); }, {p, "sonar 0", "radius_m"});
}

TEST(SonarRingErrors, MaxRangeBelowMinRange) {
  TempDir dir;
  const std::string p = dir.write(
      "r.yaml",
      ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0, min_range_m: 2, max_range_m: 1"));
  expect_error([&] { load_sonar_ring(p); }, {p, "max_range_m", "min_range_m"});
}

TEST(SonarRingErrors, NonNumericField) {
  TempDir dir;
  const std::string p =
      dir.write("r.yaml", ring_yaml("bearing_deg: left, radius_m: 0.3, heading_deg: 0"));
  expect_error([&] { load_sonar_ring(p); }, {p, "bearing_deg", "left"});
  const std::string q =
      dir.write("q.yaml", ring_yaml("bearing_deg: 0, radius_m: [1, 2], heading_deg: 0"));
  expect_error([&] { load_sonar_ring(q); }, {q, "radius_m"});
  const std::string nan =
      dir.write("n.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: .nan"));
  expect_error([&] { load_sonar_ring(nan); }, {nan, "heading_deg"});
}

TEST(SonarRingErrors, ConeOutOfRange) {
  TempDir dir;
  for (const std::string cone : {"0", "-5", "180", "200"}) {
    const std::string p = dir.write(
        "r.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0, cone_deg: " + cone));
    expect_error([&] { load_sonar_ring(p); }, {p, "cone_deg"});
  }
}

TEST(SonarRingErrors, BadSonarsAndFootprint) {
  TempDir dir;
  const std::string no_list = dir.write("a.yaml", "name: x\nsonars: 3\n");
  expect_error([&] { load_sonar_ring(no_list); }, {no_list, "sonars"});
  const std::string no_sonars = dir.write("b.yaml", "name: x\n");
  expect_error([&] { load_sonar_ring(no_sonars); }, {no_sonars, "sonars"});
  const std::string empty = dir.write("c.yaml", "name: x\nsonars: []\n");
  expect_error([&] { load_sonar_ring(empty); }, {empty, "no sonars"});
  const std::string short_fp = dir.write(
      "d.yaml",
      ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0", "footprint: [[0, 0], [1, 0]]\n"));
  expect_error([&] { load_sonar_ring(short_fp); }, {short_fp, "footprint"});
  const std::string bad_point =
      dir.write("e.yaml", ring_yaml("bearing_deg: 0, radius_m: 0.3, heading_deg: 0",
                                    "footprint: [[0, 0], [1, 0], [1, a]]\n"));
  expect_error([&] { load_sonar_ring(bad_point); }, {bad_point, "footprint"});
}

TEST(SonarRingErrors, ValidateRingBuiltInCode) {
  SonarRing ring;
  ring.name = "coded";
  expect_error([&] { validate(ring); }, {"coded", "no sonars"});
  ring.sonars.resize(3);
  EXPECT_NO_THROW(validate(ring));
  ring.sonars[2].min_range = -1.0;
  expect_error([&] { validate(ring); }, {"coded", "sonar 2", "min_range_m"});
}

// Known bug (sensors/src/sonar_ring.cpp:133 `root["name"].as<std::string>()`, and line 24 for
// non-scalar keys): these escape as YAML::TypedBadConversion instead of gridloc::Error, so
// the CLI reports an "internal error" with exit code 1. Enable once fixed.
TEST(SonarRingErrors, NonScalarNameOrKeyThrowsGridlocError) {
  TempDir dir;
  const std::string sonar = "bearing_deg: 0, radius_m: 0.3, heading_deg: 0";
  const std::string name = dir.write("a.yaml", "name: [a, b]\nsonars:\n  - {" + sonar + "}\n");
  expect_error([&] { load_sonar_ring(name); }, {name, "name"});
  const std::string key = dir.write("b.yaml", "? [a, b]\n: 1\nsonars:\n  - {" + sonar + "}\n");
  expect_error([&] { load_sonar_ring(key); }, {key, "key"});
}

// ---- readings --------------------------------------------------------------------------

class Readings : public ::testing::Test {
 protected:
  SonarRing ring = load_sonar_ring(test::ring_path());
  std::vector<double> good = std::vector<double>(14, 2.0);
};

TEST_F(Readings, GoodReadingsPass) {
  EXPECT_NO_THROW(validate_readings(ring, good));
  good[3] = 6.0;   // exactly max_range: no echo
  good[4] = 0.15;  // exactly min_range
  EXPECT_NO_THROW(validate_readings(ring, good));
}

TEST_F(Readings, WrongCount) {
  good.pop_back();
  expect_error([&] { validate_readings(ring, good); }, {"expected 14", "got 13"});
  expect_error([&] { validate_readings(ring, {}); }, {"expected 14", "got 0"});
}

TEST_F(Readings, NaN) {
  good[3] = kNaN;
  expect_error([&] { validate_readings(ring, good); }, {"range 3", "NaN"});
}

TEST_F(Readings, Negative) {
  good[0] = -0.5;
  expect_error([&] { validate_readings(ring, good); }, {"range 0", "-0.5", "negative"});
}

TEST_F(Readings, AboveMaxRange) {
  good[13] = 6.5;
  expect_error([&] { validate_readings(ring, good); }, {"range 13", "6.5", "max range"});
  good[13] = std::numeric_limits<double>::infinity();
  expect_error([&] { validate_readings(ring, good); }, {"range 13", "max range"});
}

TEST_F(Readings, BelowMinRange) {
  good[7] = 0.1;
  expect_error([&] { validate_readings(ring, good); }, {"range 7", "0.1", "min range"});
}

}  // namespace
}  // namespace gridloc

namespace gridloc {
namespace {

// Issue 14: a directory or a huge file is named; sonars and footprint points are limited.
TEST(SonarRingErrors, Limits) {
  TempDir dir;
  expect_error([&] { load_sonar_ring(dir.path().string()); },
               {dir.path().string(), "is a directory", "sonar ring file"});
  const std::string p =
      dir.write("r.yaml",
                "sonars:\n"
                "  - {bearing_deg: 0, radius_m: 0.2, heading_deg: 0}\n"
                "  - {bearing_deg: 90, radius_m: 0.2, heading_deg: 90}\n"
                "footprint: [[0.3, 0.3], [-0.3, 0.3], [-0.3, -0.3], [0.3, -0.3]]\n");
  EXPECT_EQ(load_sonar_ring(p).sonars.size(), 2u);
  ResourceLimits one_sonar;
  one_sonar.max_beams = 1;
  expect_error([&] { load_sonar_ring(p, one_sonar); }, {p, "2 sonars", "--max-beams"});
  ResourceLimits three_vertices;
  three_vertices.max_vertices = 3;
  expect_error([&] { load_sonar_ring(p, three_vertices); }, {p, "footprint", "--max-vertices"});
  ResourceLimits tiny_file;
  tiny_file.max_file_mb = 1e-6;
  expect_error([&] { load_sonar_ring(p, tiny_file); }, {p, "--max-file-mb"});
}

}  // namespace
}  // namespace gridloc
