#include "gridloc/engine/team/virtual_link.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "gridloc/grids/error.hpp"
#include "gridloc/sensors/rng.hpp"
#include "wall_geometry.hpp"

namespace gridloc {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

std::string link_name(const VirtualLink& link) {
  return "link " + std::to_string(link.from) + "-" + std::to_string(link.to);
}

std::string metres(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value << " m";
  return text.str();
}

}  // namespace

void validate(const CameraModel& camera) {
  require(std::isfinite(camera.max_range_m) && camera.max_range_m > 0.0,
          "camera max_range_m must be positive and finite");
  require(std::isfinite(camera.min_range_m) && camera.min_range_m >= 0.0 &&
              camera.min_range_m < camera.max_range_m,
          "camera min_range_m must be in [0, max_range_m)");
  require(std::isfinite(camera.length_sigma_at_max_m) && camera.length_sigma_at_max_m >= 0.0,
          "camera length_sigma_at_max_m must be >= 0 and finite");
  require(std::isfinite(camera.bearing_sigma) && camera.bearing_sigma >= 0.0,
          "camera bearing_sigma must be >= 0 and finite");
}

double length_sigma(const CameraModel& camera, double length_m) {
  const double ratio = length_m / camera.max_range_m;
  return camera.length_sigma_at_max_m * ratio * ratio;
}

void validate(const VirtualLink& link, int robots, const CameraModel& camera) {
  const std::string name = link_name(link);
  require(link.from >= 0 && link.from < robots && link.to >= 0 && link.to < robots,
          name + ": robot index out of range (the team has " + std::to_string(robots) + " robots)");
  require(link.from != link.to, name + ": a link joins two different robots");
  require(std::isfinite(link.length_m), name + ": length is not finite");
  require(link.length_m <= camera.max_range_m, name + ": " + metres(link.length_m) +
                                                   " is beyond the camera's range of " +
                                                   metres(camera.max_range_m));
  require(link.length_m >= camera.min_range_m, name + ": " + metres(link.length_m) +
                                                   " is below the camera's minimum of " +
                                                   metres(camera.min_range_m));
  require(std::isfinite(link.bearing), name + ": bearing is not finite");
  require(!std::isinf(link.back_bearing), name + ": back bearing is infinite");
}

bool line_of_sight(const MapFeatures& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  for (const MapWall& wall : map.walls)
    if (team_detail::segments_meet(a, b, wall.a, wall.b)) return false;
  return true;
}

VirtualLink measure_link(int from, int to, const Pose2& a, const Pose2& b,
                         const CameraModel& camera, std::uint64_t seed) {
  const Eigen::Vector2d delta(b.x - a.x, b.y - a.y);
  VirtualLink link;
  link.from = from;
  link.to = to;
  link.length_m = delta.norm();
  link.bearing = normalize_angle(team_detail::heading_of(delta) - a.theta);
  link.back_bearing = normalize_angle(team_detail::heading_of(-delta) - b.theta);
  if (seed != 0) {
    Rng rng(seed);
    link.length_m += length_sigma(camera, link.length_m) * rng.gaussian();
    link.bearing = normalize_angle(link.bearing + camera.bearing_sigma * rng.gaussian());
    link.back_bearing = normalize_angle(link.back_bearing + camera.bearing_sigma * rng.gaussian());
  }
  return link;
}

std::vector<VirtualLink> measurable_links(const std::vector<Pose2>& poses, const MapFeatures& map,
                                          const CameraModel& camera, std::uint64_t seed) {
  std::vector<VirtualLink> links;
  const int robots = static_cast<int>(poses.size());
  for (int i = 0; i < robots; ++i)
    for (int j = i + 1; j < robots; ++j) {
      const Eigen::Vector2d a(poses[i].x, poses[i].y), b(poses[j].x, poses[j].y);
      const double distance = (b - a).norm();
      if (distance > camera.max_range_m || distance < camera.min_range_m) continue;
      if (!line_of_sight(map, a, b)) continue;
      const std::uint64_t link_seed =
          seed == 0 ? 0 : seed * 1000003ull + static_cast<std::uint64_t>(i * robots + j + 1);
      VirtualLink link = measure_link(i, j, poses[i], poses[j], camera, link_seed);
      // Noise can carry a length past the camera's limits: that link is not measured.
      if (link.length_m > camera.max_range_m || link.length_m < camera.min_range_m) continue;
      links.push_back(link);
    }
  return links;
}

Eigen::Vector2d linked_position(const VirtualLink& link, const Pose2& a) {
  return Eigen::Vector2d(a.x, a.y) + link.length_m * team_detail::unit_at(a.theta + link.bearing);
}

double linked_heading(const VirtualLink& link, double from_heading) {
  if (std::isnan(link.back_bearing)) return std::nan("");
  return normalize_angle(from_heading + link.bearing - link.back_bearing + std::numbers::pi);
}

}  // namespace gridloc
