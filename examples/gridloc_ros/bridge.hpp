#pragma once
// The ROS node's way into gridloc. ROS 1's message headers do not compile as C++20 and
// gridloc's targets require it, so the node (node.cpp, the ROS side) and the library never
// share a source file: this header uses only the standard library and compiles as C++14 and
// up; bridge.cpp, built as C++20, implements it with gridloc's Localizer.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gridloc_ros {

struct Pose {
  double x = 0.0, y = 0.0, theta = 0.0;
};

/// A map as nav_msgs/OccupancyGrid carries it: row-major from the cell at `origin`, -1
/// unknown, 0..100 occupancy (>= occupied_threshold occupied, <= free_threshold free, else
/// unknown).
struct GridMap {
  int width = 0, height = 0;
  double resolution = 0.05;
  Pose origin;
  std::vector<std::int8_t> data;
  int occupied_threshold = 65;
  int free_threshold = 19;
};

/// One sonar as tf and its sensor_msgs/Range give it: the mount in the robot frame (the cone's
/// axis along the mount's heading), the cone's full aperture and the ranges.
struct SonarMount {
  Pose mount;
  double field_of_view = 0.20944;  ///< rad
  double min_range = 0.15, max_range = 6.0;
};

struct BridgeOptions {
  std::string map_file;   ///< a map_server YAML (used when no GridMap is given)
  std::string ring_file;  ///< sonar mode: the ring (gridloc YAML), sonars in frame order...
  std::vector<SonarMount> sonars;  ///< ...or the sonars from tf (used when ring_file is empty)
  double laser_max_range = 20.0;   ///< laser mode: returns at or beyond are no return
  Pose laser_mount;                ///< laser mode: the laser in the robot frame
  double resolution = 0.0;         ///< the search's cell (m); 0: the map's (laser) or 0.1 (sonar)
  /// The odometry model the places' covariances grow by (share of path, degrees per metre).
  double odometry_error_per_m = 0.05;
  double odometry_turn_deg_per_m = 5.0;
  /// From no prior, the first place is `localized` only once the drive has borne it out
  /// (gridloc::JumpGateOptions::settle_first); false: one scan may localize.
  bool settle_first = true;
  /// Laser mode: added to the reported covariance (m and degrees, one standard deviation;
  /// gridloc::LocalizerOptions::reported_floor_m): the map's own error, which a scan cannot see.
  double reported_floor_m = 0.02;
  double reported_floor_deg = 0.5;
};

struct Answer {
  Pose pose;
  std::array<double, 36> covariance{};  ///< ROS's 6x6 (x y z roll pitch yaw), row-major
  std::string verdict;                  ///< "localized", "ambiguous" or "not localized"
  double confidence = 0.0;
  int hypotheses = 0;
  double elapsed_ms = 0.0;
  int search_slices_done = 0, search_slices = 0;  ///< a re-search under way...
  double search_progress = 0.0;                   ///< ...and the share of it done
  /// Why the answer is "not localized" ("none" otherwise): gridloc::HeldBack's name.
  std::string held_back = "none";
};

/// One Localizer (engine/include/gridloc/engine/localizer/localizer.hpp) built on a map and a
/// sonar ring or a laser. Every method throws std::runtime_error with gridloc's one-line
/// message on bad input.
class Bridge {
 public:
  /// Builds the localizer on `map` (or options.map_file when `map` is empty).
  Bridge(const GridMap& map, const BridgeOptions& options);
  ~Bridge();
  Bridge(const Bridge&) = delete;
  Bridge& operator=(const Bridge&) = delete;

  bool sonar() const;
  int sonar_count() const;  ///< sonars in the ring (0 for a laser)
  void add_odometry(const Pose& odometry);
  /// The robot is at `pose` with `covariance` (ROS 6x6 row-major: x, y and yaw are read).
  void set_prior(const Pose& pose, const std::array<double, 36>& covariance);
  /// Forgets the places: the next observation searches the whole map.
  void reset();
  /// One firing of the ring, in ring order, as the driver gives it (REP 117: +inf no echo,
  /// -inf too close).
  Answer add_sonar(double time_s, const std::vector<double>& ranges);
  /// One laser scan (sensor frame): ranges from angle_min by angle_increment.
  Answer add_scan(double time_s, double angle_min, double angle_increment, double range_max,
                  const std::vector<float>& ranges);
  bool has_answer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gridloc_ros
