#include "gridloc/sensors/segment_world.hpp"

#include <cmath>
#include <string>

#include "gridloc/grids/error.hpp"

namespace gridloc {
namespace {

constexpr RayTolerances kBeamTolerances{.parallel = 1e-12, .slack = 1e-12, .origin_counts = false};

}  // namespace

RangeScan simulate_segment_scan(const std::vector<WallSegment>& walls, const Pose2& pose, int beams,
                                double first_angle, double angle_step, double max_range) {
  if (beams < 1) {
    throw Error("simulate_segment_scan: beams must be >= 1, got " + std::to_string(beams));
  }
  if (!(angle_step > 0.0) || !std::isfinite(angle_step)) {
    throw Error("simulate_segment_scan: angle_step must be positive and finite, got " +
                std::to_string(angle_step));
  }
  if (!(max_range > 0.0) || !std::isfinite(max_range)) {
    throw Error("simulate_segment_scan: max_range must be positive and finite, got " +
                std::to_string(max_range));
  }
  if (!std::isfinite(first_angle)) {
    throw Error("simulate_segment_scan: first_angle must be finite, got " +
                std::to_string(first_angle));
  }
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw Error("simulate_segment_scan: pose must be finite, got (" + std::to_string(pose.x) +
                ", " + std::to_string(pose.y) + ", " + std::to_string(pose.theta) + ")");
  }
  RangeScan scan;
  scan.max_range = max_range;
  scan.angles.reserve(static_cast<std::size_t>(beams));
  scan.ranges.reserve(static_cast<std::size_t>(beams));
  const Eigen::Vector2d o(pose.x, pose.y);
  for (int k = 0; k < beams; ++k) {
    const double bearing = first_angle + angle_step * k;
    const Eigen::Vector2d d(std::cos(pose.theta + bearing), std::sin(pose.theta + bearing));
    // t > 0 ahead, u in [0, 1] on the wall with a hair of slack (a beam through a vertex
    // shared by two walls meets one).
    const double best = ray_distance(o, d, walls, kBeamTolerances);
    scan.angles.push_back(bearing);
    scan.ranges.push_back(best < max_range ? best : max_range);
  }
  return scan;
}

std::vector<WallSegment> seed004_hallway() {
  const auto w = [](double ax, double ay, double bx, double by) {
    return WallSegment{{ax, ay}, {bx, by}};
  };
  return {// top wall with a door recess
          w(-4, 1, 1, 1), w(1, 1, 1, 1.6), w(1, 1.6, 2, 1.6), w(2, 1.6, 2, 1), w(2, 1, 6, 1),
          // end walls
          w(6, 1, 6, -1), w(-4, -1, -4, 1),
          // bottom wall with an alcove and a pillar
          w(6, -1, 3.8, -1), w(3.8, -1, 3.8, -1.5), w(3.8, -1.5, 3, -1.5), w(3, -1.5, 3, -1),
          w(3, -1, -1.2, -1), w(-1.2, -1, -1.2, -0.7), w(-1.2, -0.7, -1.5, -0.7),
          w(-1.5, -0.7, -1.5, -1), w(-1.5, -1, -4, -1),
          // a square column
          w(-2.5, 0.2, -2.2, 0.2), w(-2.2, 0.2, -2.2, 0.5), w(-2.2, 0.5, -2.5, 0.5),
          w(-2.5, 0.5, -2.5, 0.2)};
}

}  // namespace gridloc
