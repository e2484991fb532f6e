#pragma once
// Random-case helpers shared by the property tests: portable uniform draws and random scans.
#include <algorithm>
#include <numbers>
#include <random>

#include "gridloc/sensors/range_scan.hpp"

namespace gridloc::test {

// These draw from the raw generator output because std::mt19937 is specified exactly but
// <random>'s distributions are not: fixed-seed cases stay the same on every standard library.

/// An int in [lo, hi] (inclusive); portable, unlike std::uniform_int_distribution.
inline int uniform_int(std::mt19937& rng, int lo, int hi) {
  return lo + static_cast<int>(rng() % static_cast<unsigned>(hi - lo + 1));
}

/// A double in [lo, hi); portable, unlike std::uniform_real_distribution.
inline double uniform_real(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}

/// A float in [lo, hi] (float rounding may reach hi); portable, unlike <random>'s.
inline float uniform_float(std::mt19937& rng, float lo, float hi) {
  return lo + (hi - lo) * static_cast<float>(static_cast<double>(rng()) / 4294967296.0);
}

/// A random scan: even or random angles, ranges in (0, max_range) with some beams without a
/// return (at or beyond the max range) and some of range 0, the edge cases scan models must
/// handle; at least one return, since validate() requires it.
inline RangeScan random_scan(std::mt19937& rng, int beams, double max_range) {
  RangeScan scan;
  scan.max_range = max_range;
  const bool even = uniform_int(rng, 0, 1) == 0;
  const double a0 = uniform_real(rng, -std::numbers::pi, std::numbers::pi);
  for (int k = 0; k < beams; ++k) {
    scan.angles.push_back(even ? a0 + 2.0 * std::numbers::pi * k / beams
                               : uniform_real(rng, -std::numbers::pi, std::numbers::pi));
    const int kind = uniform_int(rng, 0, 19);
    double r = uniform_real(rng, 0.0, max_range);
    if (kind < 3) r = kind == 0 ? max_range : max_range + uniform_real(rng, 0.0, 3.0);
    if (kind == 3) r = 0.0;
    scan.ranges.push_back(r);
  }
  if (std::none_of(scan.ranges.begin(), scan.ranges.end(),
                   [&](double r) { return r < max_range; })) {
    scan.ranges[0] = 0.5 * max_range;
  }
  return scan;
}

}  // namespace gridloc::test
