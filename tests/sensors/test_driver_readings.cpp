// Tests of sensors/src/driver_readings.cpp: REP 117's +inf / -inf, too close, a hair too far.
#include "gridloc/sensors/driver_readings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "test_support.hpp"

namespace gridloc {
namespace {

const SonarRing& ring() {
  static const SonarRing loaded = load_sonar_ring(test::ring_path());
  return loaded;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(DriverReadings, InfinitiesAndTooCloseAreReadingsNotErrors) {
  std::vector<double> raw(ring().sonars.size(), 2.0);
  raw[0] = kInf;                                // no echo
  raw[1] = -kInf;                               // too close
  raw[2] = 0.05;                                // below the 0.15 m minimum: too close
  raw[3] = ring().sonars[3].max_range + 0.005;  // a hair above max range: no echo
  const DriverReadings readings = from_driver(ring(), raw);
  EXPECT_EQ(readings.ranges[0], ring().sonars[0].max_range);
  EXPECT_FALSE(readings.rejected[0]);
  EXPECT_TRUE(readings.rejected[1]);
  EXPECT_TRUE(readings.rejected[2]);
  EXPECT_EQ(readings.ranges[3], ring().sonars[3].max_range);
  EXPECT_FALSE(readings.rejected[3]);
  EXPECT_EQ(readings.ranges[4], 2.0);
  EXPECT_FALSE(readings.rejected[4]);
  EXPECT_NO_THROW(validate_readings(ring(), readings.ranges, readings.rejected));
}

TEST(DriverReadings, TheBoundsThemselves) {
  const SonarSpec& sonar = ring().sonars[0];
  std::vector<double> raw(ring().sonars.size(), 2.0);
  raw[0] = sonar.min_range;  // exactly the minimum: a reading
  raw[1] = 0.0;              // touching: too close
  raw[2] = sonar.max_range;  // exactly the maximum: no echo
  raw[3] = sonar.max_range + 0.01;
  const DriverReadings readings = from_driver(ring(), raw, 0.01);
  EXPECT_FALSE(readings.rejected[0]);
  EXPECT_EQ(readings.ranges[0], sonar.min_range);
  EXPECT_TRUE(readings.rejected[1]);
  EXPECT_EQ(readings.ranges[2], sonar.max_range);
  EXPECT_EQ(readings.ranges[3], ring().sonars[3].max_range);
  raw[3] = ring().sonars[3].max_range + 0.02;
  test::expect_error([&] { from_driver(ring(), raw, 0.01); },
                     {"sonar 3", "max range 6", "by more than 0.01"});
  test::expect_error([&] { from_driver(ring(), raw, std::nan("")); }, {"slack"});
  test::expect_error([&] { from_driver(ring(), raw, -1.0); }, {"slack"});
}

TEST(DriverReadings, NaNNegativeAndFarValuesAreErrorsNamingTheSonar) {
  std::vector<double> raw(ring().sonars.size(), 2.0);
  raw[6] = std::nan("");
  test::expect_error([&] { from_driver(ring(), raw); }, {"sonar 6", "NaN"});
  raw[6] = -0.5;
  test::expect_error([&] { from_driver(ring(), raw); }, {"sonar 6", "negative"});
  raw[6] = 9.0;
  test::expect_error([&] { from_driver(ring(), raw); }, {"sonar 6", "max range"});
  test::expect_error([&] { from_driver(ring(), {1.0, 2.0}); }, {"expected 14 values", "got 2"});
  test::expect_error([&] { from_driver(ring(), std::vector<double>(ring().sonars.size(), -kInf)); },
                     {"every sonar", "too close"});
}

}  // namespace
}  // namespace gridloc
