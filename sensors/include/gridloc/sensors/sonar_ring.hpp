#pragma once
/// A ring of ultrasonic sonars on a robot (seed 001 §3, Fig. 2-3).
/// Robot frame: x forward, y left, angles CCW from +x, metres and radians.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gridloc/grids/limits.hpp"

namespace gridloc {

/// One sonar: mounted at polar position (bearing, radius) about the robot centre, its axis
/// pointing at `heading`, emitting a cone of full aperture `cone`.
struct SonarSpec {
  double bearing = 0.0;   ///< beta_c, rad
  double radius = 0.0;    ///< r_c, m
  double heading = 0.0;   ///< epsilon_c, rad (direction of the cone axis)
  double cone = 0.20944;  ///< alpha_c, full aperture, rad (12 degrees)
  double min_range = 0.15;
  double max_range = 6.0;  ///< a reading >= max_range means "no echo"
};

/// The robot's outline in the robot frame (a simple polygon, counter-clockwise or not).
struct Footprint {
  std::vector<Eigen::Vector2d> polygon;
};

struct SonarRing {
  std::string name;
  std::vector<SonarSpec> sonars;
  Footprint footprint;

  /// Largest distance from the robot centre any reading or the footprint can reach.
  double reach() const;
};

/// Loads a ring from YAML (see maps/sensors/). Unknown keys, wrong types and impossible
/// values throw gridloc::Error naming the file and field; so do a missing file, a directory
/// or device, a file over limits.max_file_mb, more sonars than limits.max_beams and a
/// footprint of more than limits.max_vertices points.
SonarRing load_sonar_ring(const std::string& yaml_path, const ResourceLimits& limits = {});

/// Checks a ring built in code; throws gridloc::Error naming the sonar and field.
void validate(const SonarRing& ring);

/// Checks one set of readings against the ring: count, finite, not negative, within
/// [min_range, max_range] (a value equal to max_range means no echo). `rejected` (empty = none)
/// marks sonars an echo filter rejected: it must hold one flag per sonar and leave at least
/// one reading.
void validate_readings(const SonarRing& ring, const std::vector<double>& ranges,
                       const std::vector<bool>& rejected = {});

/// True when the footprint polygon contains point p (robot frame).
bool footprint_contains(const Footprint& footprint, const Eigen::Vector2d& p);

}  // namespace gridloc
