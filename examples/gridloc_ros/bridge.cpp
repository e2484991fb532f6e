// The bridge's C++20 side: gridloc's Localizer behind the ROS-free interface of bridge.hpp.
#include "bridge.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "gridloc/engine/localizer/localizer.hpp"
#include "gridloc/grids/error.hpp"
#include "gridloc/grids/map_io.hpp"
#include "gridloc/sensors/sonar_ring.hpp"

namespace gridloc_ros {
namespace {

gridloc::Pose2 to_gridloc(const Pose& pose) {
  return {pose.x, pose.y, pose.theta};
}

/// An OccupancyGrid's cells as gridloc's three states.
gridloc::OccupancyMap to_map(const GridMap& grid) {
  if (grid.width <= 0 || grid.height <= 0 || !(grid.resolution > 0.0) ||
      grid.data.size() != static_cast<std::size_t>(grid.width) * grid.height) {
    throw gridloc::Error("map: the occupancy grid's size, resolution or data is inconsistent");
  }
  gridloc::GridGeometry geometry;
  geometry.width = grid.width;
  geometry.height = grid.height;
  geometry.resolution = grid.resolution;
  geometry.origin = {grid.origin.x, grid.origin.y};
  geometry.yaw = grid.origin.theta;
  gridloc::OccupancyMap map(geometry, gridloc::CellState::Unknown);
  for (std::size_t i = 0; i < grid.data.size(); ++i) {
    const int v = grid.data[i];
    if (v >= grid.occupied_threshold) map.cells[i] = gridloc::CellState::Occupied;
    if (v >= 0 && v <= grid.free_threshold) map.cells[i] = gridloc::CellState::Free;
  }
  return map;
}

gridloc::LocalizerOptions localizer_options(const BridgeOptions& options, double resolution) {
  gridloc::LocalizerOptions localizer;
  localizer.correlation.resolution = resolution;
  localizer.odometry_error_per_m = localizer.jump_gate.odometry_error_per_m =
      options.odometry_error_per_m;
  localizer.odometry_turn_error_per_m = localizer.jump_gate.odometry_turn_error_per_m =
      gridloc::deg2rad(options.odometry_turn_deg_per_m);
  localizer.jump_gate.settle_first = options.settle_first;
  localizer.reported_floor_m = options.reported_floor_m;
  localizer.reported_floor_rad = gridloc::deg2rad(options.reported_floor_deg);
  return localizer;
}

/// A ring of the sonars tf placed: each mount as gridloc's polar position and cone heading.
gridloc::SonarRing ring_of(const std::vector<SonarMount>& sonars) {
  gridloc::SonarRing ring;
  ring.name = "from tf";
  for (const SonarMount& sonar : sonars) {
    gridloc::SonarSpec spec;
    spec.bearing = std::atan2(sonar.mount.y, sonar.mount.x);
    spec.radius = std::hypot(sonar.mount.x, sonar.mount.y);
    spec.heading = sonar.mount.theta;
    spec.cone = sonar.field_of_view;
    spec.min_range = sonar.min_range;
    spec.max_range = sonar.max_range;
    ring.sonars.push_back(spec);
  }
  gridloc::validate(ring);
  return ring;
}

bool sonar_mode(const BridgeOptions& options) {
  return !options.ring_file.empty() || !options.sonars.empty();
}

gridloc::Localizer make_localizer(gridloc::OccupancyMap map, const BridgeOptions& options) {
  if (sonar_mode(options)) {
    const double resolution = options.resolution > 0.0 ? options.resolution : 0.1;
    gridloc::SonarRing ring = options.ring_file.empty()
                                  ? ring_of(options.sonars)
                                  : gridloc::load_sonar_ring(options.ring_file);
    return gridloc::Localizer(std::move(map), std::move(ring),
                              localizer_options(options, resolution));
  }
  const double resolution = options.resolution > 0.0 ? options.resolution : map.geometry.resolution;
  gridloc::LaserSensor laser;
  laser.mount = to_gridloc(options.laser_mount);
  laser.max_range = options.laser_max_range;
  return gridloc::Localizer(std::move(map), laser, localizer_options(options, resolution));
}

/// Runs `what`, turning gridloc's errors into std::runtime_error (the ROS side need not
/// know gridloc::Error).
template <class F>
auto guarded(F&& what) {
  try {
    return what();
  } catch (const gridloc::Error& e) {
    throw std::runtime_error(e.what());
  }
}

}  // namespace

struct Bridge::Impl {
  Impl(gridloc::OccupancyMap map, const BridgeOptions& options)
      : sonar(sonar_mode(options)), localizer(make_localizer(std::move(map), options)) {}
  bool sonar;
  gridloc::Localizer localizer;
  bool answered = false;

  /// Localizes `observation` (sonar ranges or a scan) and answers, timed.
  template <class Observation>
  Answer observe(double time_s, const Observation& observation) {
    const auto start = std::chrono::steady_clock::now();
    localizer.add_observation(time_s, observation);
    return answer(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }

  Answer answer(double elapsed_ms) {
    answered = true;
    const gridloc::Estimate e = localizer.estimate();
    const gridloc::LocalizerStatus status = localizer.status();
    Answer a;
    a.pose = {e.pose.x, e.pose.y, e.pose.theta};
    const int axes[3] = {0, 1, 5};  // x, y, yaw in ROS's 6x6
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) a.covariance[axes[r] * 6 + axes[c]] = e.covariance(r, c);
    }
    a.verdict = gridloc::to_string(e.verdict);
    a.confidence = e.confidence;
    a.hypotheses = static_cast<int>(e.alternatives.size());
    a.elapsed_ms = elapsed_ms;
    a.search_slices_done = status.search_slices_done;
    a.search_slices = status.search_slices;
    a.search_progress = status.search_progress;
    a.held_back = gridloc::to_string(status.held_back);
    return a;
  }
};

Bridge::Bridge(const GridMap& map, const BridgeOptions& options) {
  impl_ = guarded([&] {
    gridloc::OccupancyMap occupancy =
        map.data.empty() ? gridloc::load_ros_map(options.map_file) : to_map(map);
    return std::make_unique<Impl>(std::move(occupancy), options);
  });
}

Bridge::~Bridge() = default;

bool Bridge::sonar() const {
  return impl_->sonar;
}

int Bridge::sonar_count() const {
  return impl_->sonar ? static_cast<int>(impl_->localizer.estimator().ring().sonars.size()) : 0;
}

void Bridge::add_odometry(const Pose& odometry) {
  guarded([&] {
    impl_->localizer.add_odometry(to_gridloc(odometry));
    return 0;
  });
}

void Bridge::set_prior(const Pose& pose, const std::array<double, 36>& covariance) {
  guarded([&] {
    Eigen::Matrix3d c;
    const int axes[3] = {0, 1, 5};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) c(r, k) = covariance[axes[r] * 6 + axes[k]];
    }
    impl_->localizer.set_prior(to_gridloc(pose), c);
    return 0;
  });
}

void Bridge::reset() {
  impl_->localizer.reset();
}

Answer Bridge::add_sonar(double time_s, const std::vector<double>& ranges) {
  return guarded([&] { return impl_->observe(time_s, ranges); });
}

Answer Bridge::add_scan(double time_s, double angle_min, double angle_increment, double range_max,
                        const std::vector<float>& ranges) {
  return guarded([&] {
    gridloc::RangeScan scan;
    scan.max_range = range_max;
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      const double r = ranges[i];
      // REP 117: NaN (invalid) and -inf (too close) say nothing of where the walls are;
      // +inf is no echo within range.
      if (std::isnan(r) || r < 0.0) continue;
      scan.angles.push_back(angle_min + angle_increment * static_cast<double>(i));
      scan.ranges.push_back(std::min(r, range_max));
    }
    return impl_->observe(time_s, scan);
  });
}

bool Bridge::has_answer() const {
  return impl_->answered;
}

}  // namespace gridloc_ros
