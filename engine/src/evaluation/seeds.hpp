#pragma once
// The seeds of the evaluation protocols' trials (shared by sonar_protocol.cpp and
// sector_protocol.cpp; internal).
#include <cstdint>

#include "gridloc/sensors/rng.hpp"

namespace gridloc {

/// A seed derived from two others.
inline std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  return Rng(a * 0x100000001B3ull ^ b).next();
}

/// The seed of trial `trial` on the map at index `map` of a run seeded with `seed`.
inline std::uint64_t trial_seed(std::uint64_t seed, std::uint64_t map, int trial) {
  return mix(mix(seed, map), static_cast<std::uint64_t>(trial));
}

}  // namespace gridloc
