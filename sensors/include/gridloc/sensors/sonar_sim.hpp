#pragma once
/// A sonar simulator on a map, seed 001 §4's "graphic method": a sonar reads the distance to
/// the first obstacle inside its emission cone. Seeded and deterministic.
#include <cstdint>
#include <vector>

#include "gridloc/grids/grid.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc {

struct SonarSimOptions {
  std::uint64_t seed = 1;
  double range_sigma_m = 0.0;     ///< Gaussian range noise, constant part (m)
  double range_sigma_frac = 0.0;  ///< Gaussian range noise, proportional part (of the range)
  double dropout_prob = 0.0;      ///< probability that a sonar hears no echo at all
  /// Specular reflection: a ray meeting a surface at an incidence angle (from the surface
  /// normal) above this returns no echo; 90 degrees turns it off (the paper's rugged walls).
  double specular_incidence_deg = 90.0;
  double crosstalk_prob = 0.0;  ///< probability of a wrong short echo (another sonar's ping)
  double ray_step_deg = 0.25;   ///< angular spacing of the rays traced inside each cone

  /// Noise we use as "realistic" in the evaluation: 2 cm + 1 % range noise, 2 % dropouts,
  /// specular loss beyond 75 degrees of incidence, 1 % crosstalk.
  static SonarSimOptions realistic(std::uint64_t seed);
  /// Noise strong enough to make the matcher fail now and then: 3 cm + 2 % range noise, 5 %
  /// dropouts, specular loss beyond 60 degrees, 5 % crosstalk.
  static SonarSimOptions harsh(std::uint64_t seed);
};

/// Simulates one reading per sonar of `ring` for a robot at world pose `pose` on `map`.
/// Unknown cells are transparent; rays leaving the map hear nothing. A reading with no echo
/// is exactly the sonar's max_range; echoes are clamped to [min_range, max_range).
std::vector<double> simulate_sonar(const OccupancyMap& map, const SonarRing& ring,
                                   const Pose2& pose, const SonarSimOptions& options = {});

}  // namespace gridloc
